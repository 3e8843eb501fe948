"""Oh No, Kitten Avalanche!: arrivals, dragging, flinging, and which node is grabbed."""

from __future__ import annotations

import numpy as np
import pytest

from sinews.scenes import KittenAvalanche, SceneEvent, SceneInput
from sinews.scenes.kitten import KITTEN_NODES, kitten


def landed(seed: int) -> KittenAvalanche:
    """One kitten, arrived and settled on the floor."""
    scene = KittenAvalanche(np.random.default_rng(seed), pool=1)
    for _ in range(150):
        scene.step()
    assert scene.on_screen[0]
    return scene


def drag(scene: KittenAvalanche, part: str, offset: tuple[float, float], frames: int) -> float:
    """Press on a kitten node, hold the pointer ``offset`` away; return the largest strain."""
    node = scene.parts[0].nodes.start + KITTEN_NODES.index(part)
    start = scene.world.positions[node].copy()
    goal = tuple(start + offset)
    edges = scene.parts[0].edges
    pairs = scene.world.layout.body.edges[edges]
    rest = scene.world.layout.body.rest_length[edges]
    strain = 0.0
    for k in range(frames):
        frame = scene.step(SceneInput(pointer=goal if k else tuple(start), pressed=True))
        assert frame.grabbed == node
        pos = scene.world.positions
        length = np.hypot(*(pos[pairs[:, 1]] - pos[pairs[:, 0]]).T)
        strain = max(strain, float(np.abs(length / rest - 1.0).max()))
    return strain


def test_kittens_have_every_part_and_vary_with_the_seed() -> None:
    a, b = kitten(np.random.default_rng(1)), kitten(np.random.default_rng(2))
    assert a.names == b.names == KITTEN_NODES
    assert not np.allclose(a.rest, b.rest)
    assert a.rest[:, 1].min() > 0.0  # standing on the floor
    tail, spine = a.index("tail_tip"), a.index("back")
    assert a.mass[tail] < 0.5 * a.mass[spine]


def test_a_dragged_kitten_flies_off_screen_and_counts() -> None:
    scene = landed(0)
    node = scene.parts[0].nodes.start + KITTEN_NODES.index("back")
    _, _, x1, y1 = scene.screen
    start = scene.world.positions[node].copy()
    goal = np.array([x1 + 1.5, y1])
    for k in range(31):  # 0.5 s, speeding up: a fling
        pointer = start + (goal - start) * (k / 30) ** 2
        scene.step(SceneInput(pointer=(pointer[0], pointer[1]), pressed=True))
    events: list[SceneEvent] = []
    for _ in range(120):
        frame = scene.step(SceneInput(pointer=(goal[0], goal[1]), pressed=False))
        events += frame.events
        if scene.score:
            pos = scene.world.positions[scene.parts[0].nodes]
            assert not scene.world.node_visible[scene.parts[0].nodes].any()  # parked
            assert np.all(pos[:, 0] > x1 + 100.0)  # far away
            break
    assert events[0].kind == "flung" and events[0].ids == (0,)
    assert frame.score == 1
    frame = scene.step()  # the pool's only kitten arrives again
    assert [e.kind for e in frame.events] == ["spawn"]
    assert not scene.world.failed


@pytest.mark.parametrize("seed", [3, 5, 7])
def test_the_tail_gives_way_where_the_spine_carries_the_body(seed: int) -> None:
    # the same pull, the same kitten: only which node is held differs
    strain = {part: drag(landed(seed), part, (1.5, 1.0), 30) for part in ("back", "tail_tip")}
    assert strain["tail_tip"] > 1.5 * strain["back"]  # measured 1.9x to 4.5x


@pytest.mark.parametrize("part", ["head", "near_ear", "tail_tip", "front_paw", "belly"])
def test_any_node_can_be_yanked_hard_without_blowing_up(part: str) -> None:
    scene = landed(1)
    drag(scene, part, (-4.0, 3.0), 40)
    assert not scene.world.failed


def test_arrivals_come_faster_and_flung_kittens_come_back() -> None:
    scene = KittenAvalanche(np.random.default_rng(2), pool=8)
    times = []
    for _ in range(12 * 60):
        frame = scene.step()
        times += [frame.time for e in frame.events if e.kind == "spawn"]
    gaps = np.diff(times)
    assert len(times) == 8  # the whole pool is out
    assert np.all(np.diff(gaps) < 0) and gaps[-1] < 0.8 * gaps[0]
    assert scene.score == 0  # nobody threw one
    # kitten 0 leaves without the player's help: it wandered, and comes back
    scene.world.positions[scene.parts[0].nodes] += [0.0, 50.0]
    frame = scene.step()
    assert [(e.kind, e.ids) for e in frame.events] == [("wandered", (0,))]
    assert [(e.kind, e.ids) for e in scene.step().events] == [("spawn", (0,))]
    assert scene.score == 0 and scene.world.node_visible[scene.parts[0].nodes].all()
