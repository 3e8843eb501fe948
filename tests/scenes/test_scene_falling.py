"""Falling for You: longing, linking, balloons, babies, and breaking up only by the player."""

from __future__ import annotations

import numpy as np
import pytest

from sinews.scenes import FallingForYou, SceneInput

MUTUAL = [[False, True], [True, False]]


def couple(seed: int, loves: list[list[bool]] = MUTUAL) -> FallingForYou:
    return FallingForYou(np.random.default_rng(seed), n_adults=2, n_babies=1, loves=loves)


def play_until(scene: FallingForYou, kind: str, seconds: float) -> float:
    """Step until an event of ``kind``; return its time (fail if it never comes)."""
    for _ in range(round(seconds * 60)):
        frame = scene.step()
        if any(event.kind == kind for event in frame.events):
            return frame.time
    pytest.fail(f"no {kind!r} within {seconds} s")


def centroid_y(scene: FallingForYou, doll: int) -> float:
    return float(scene.world.positions[scene.dolls[doll].nodes, 1].mean())


def centroid_x(scene: FallingForYou, doll: int) -> float:
    return float(scene.world.positions[scene.dolls[doll].nodes, 0].mean())


def arm_stretch(scene: FallingForYou, doll: int) -> float:
    """Longest shoulder-to-hand distance of a doll over its rest distance."""
    names, world = scene.world.layout.body.names, scene.world
    ratios = []
    for side in ("l", "r"):
        i, j = (names.index(f"doll{doll}.{side}_{part}") for part in ("shoulder", "hand"))
        now = np.hypot(*(world.positions[j] - world.positions[i]))
        ratios.append(now / np.hypot(*(world.shape[j] - world.shape[i])))
    return float(max(ratios))


@pytest.mark.parametrize("seed", [0, 1])
def test_mutual_lovers_link_a_balloon_appears_and_the_pair_rises(seed: int) -> None:
    scene = couple(seed)
    before = centroid_y(scene, 0)
    linked_at = play_until(scene, "link", 10.0)
    assert centroid_y(scene, 0) < before  # they were falling
    balloons = [i for i, shape in enumerate(scene.world.layout.node_shapes) if shape == "heart"]
    shown = [i for i in balloons if scene.world.node_visible[i]]
    assert len(shown) == 1 and scene.world.weight[shown[0]] < 0  # one balloon, pulling up
    assert scene.score == 1
    low = centroid_y(scene, 0)
    for _ in range(4 * 60):
        scene.step()
    assert centroid_y(scene, 0) > low + 0.3  # lifted, together
    assert centroid_y(scene, 1) > low - 0.5
    assert linked_at < 10.0 and scene.romance.link_tension(scene.world)


def test_a_baby_comes_with_its_own_balloon_and_holds_a_parents_hand() -> None:
    scene = couple(0)
    play_until(scene, "link", 10.0)
    play_until(scene, "baby", scene.romance.tuning.baby_delay + 0.5)
    baby = scene.dolls[2]
    assert scene.world.node_visible[baby.nodes].all()
    assert scene.world.edge_visible[baby.edges].all()  # a whole little body, springs and all
    assert np.all(scene.world.strength[baby.edges] == scene.world.layout.body.strength[baby.edges])
    assert len(scene.romance.link_tension(scene.world)) == 2  # the couple, and baby to parent
    hearts = [i for i, s in enumerate(scene.world.layout.node_shapes) if s == "heart"]
    assert sum(scene.world.node_visible[i] for i in hearts) == 2


def test_one_sided_love_stretches_the_lovers_arm_while_the_other_drifts() -> None:
    scene = couple(0, loves=[[False, True], [False, False]])
    lover, indifferent = 1.0, 1.0
    for _ in range(8 * 60):
        frame = scene.step()
        assert not frame.events  # never a link
        lover = max(lover, arm_stretch(scene, 0))
        indifferent = max(indifferent, arm_stretch(scene, 1))
    assert lover > 1.2  # reaching out, arm longer than at rest
    assert indifferent < 1.1


def test_links_never_break_on_their_own_over_a_long_run() -> None:
    for seed in (0, 3):
        scene = FallingForYou(np.random.default_rng(seed))
        strongest = 0.0
        for _ in range(40 * 60):
            frame = scene.step()
            assert all(event.kind != "break" for event in frame.events)
            strongest = max([strongest, *scene.romance.link_tension(scene.world).values()])
        assert scene.score >= 1
        assert strongest < 0.6 * scene.romance.tuning.break_force  # gusts, balloons, longing


def test_only_the_players_push_breaks_a_link() -> None:
    scene = couple(1)
    play_until(scene, "link", 10.0)
    for _ in range(5 * 60):  # holding hands for a while: nothing breaks
        frame = scene.step()
        assert all(event.kind != "break" for event in frame.events)
    away = float(np.sign(centroid_x(scene, 0) - centroid_x(scene, 1)))
    pushed = 0
    while not any(event.kind == "break" for event in scene.step(SceneInput(push=away)).events):
        pushed += 1
        assert pushed < 3 * 60, "the push did not part them"
    assert pushed > 10  # the springs held on for a while first
    assert scene.romance.is_single(1)  # apart (the baby still holds doll 0's other hand)
    for _ in range(60):  # heartbroken: no new link straight away
        assert all(event.kind != "link" for event in scene.step().events)


def test_the_camera_follows_the_main_doll() -> None:
    scene = couple(0)
    for _ in range(90):
        frame = scene.step(SceneInput(push=-1.0))
    x, y = scene.world.positions[scene.dolls[0].nodes].mean(axis=0)
    assert frame.camera == pytest.approx((x, y))
