"""Development: random genomes grow bodies that stand and stay humanoid."""

from __future__ import annotations

import numpy as np
import pytest

from sinews.dancers import DANCER_ENGINE, EDGE_NAMES, NODES, DancerGenome, develop
from sinews.dancers.develop import MIN_PULL
from sinews.springmass import Body, BodyBatch, SimState, simulate

N_RANDOM = 300


def idx(name: str) -> int:
    return NODES.index(name)


def test_body_has_the_tensegrity_humanoid_graph() -> None:
    body = develop(DancerGenome.neutral())
    assert body.names == NODES
    assert body.n_edges == len(EDGE_NAMES)
    for name in ("head", "neck", "chest", "pelvis", "l_hand", "r_foot", "l_knee", "r_elbow"):
        assert name in body.names
    pose = body.rest
    assert pose[idx("head"), 1] > pose[idx("chest"), 1] > pose[idx("pelvis"), 1]
    assert pose[idx("pelvis"), 1] > pose[idx("l_knee"), 1] > pose[idx("l_foot"), 1]
    assert pose[idx("l_hand"), 0] < 0 < pose[idx("r_hand"), 0]
    feet = [idx("l_foot"), idx("r_foot")]
    np.testing.assert_allclose(pose[feet, 1], body.radius[feet])  # standing on the floor


def test_main_modifiers_shape_the_body() -> None:
    base = DancerGenome.neutral()
    lanky = develop(base.replace(lankiness=1.0))
    stubby = develop(base.replace(lankiness=0.0))
    leg = (idx("l_hip"), idx("l_foot"))
    assert np.ptp(lanky.rest[list(leg), 1]) > 1.2 * np.ptp(stubby.rest[list(leg), 1])
    bulky, thin = develop(base.replace(bulkiness=1.0)), develop(base.replace(bulkiness=0.0))
    assert bulky.mass.sum() > 1.8 * thin.mass.sum()
    assert bulky.radius.mean() > 1.5 * thin.radius.mean()
    stiff, soft = develop(base.replace(stiffness=1.0)), develop(base.replace(stiffness=0.0))
    # a soft body's springs are floored (develop.MIN_PULL) so its short ones hold their length
    assert stiff.strength.mean() > 2 * soft.strength.mean()
    assert np.all(soft.strength * soft.rest_length >= MIN_PULL[0] - 1e-9)
    inverted = develop(base.replace(torso_triangularity=1.0))
    pear = develop(base.replace(torso_triangularity=0.0))

    def ratio(body: Body) -> float:
        rest = body.rest
        return float(rest[idx("r_shoulder"), 0] / rest[idx("r_hip"), 0])

    assert ratio(inverted) > 2.0 > 1.0 > ratio(pear)


def test_development_is_deterministic_and_colourful() -> None:
    genome = DancerGenome.random(np.random.default_rng(4))
    one, two = develop(genome), develop(genome)
    np.testing.assert_array_equal(one.rest, two.rest)
    np.testing.assert_array_equal(one.strength, two.strength)
    assert one.colors is not None and len({tuple(c) for c in one.colors}) > 5


@pytest.fixture(scope="module")
def random_crowd() -> tuple[BodyBatch, np.ndarray, SimState]:
    rng = np.random.default_rng(2024)
    genomes = [DancerGenome.random(rng) for _ in range(N_RANDOM)]
    batch = BodyBatch.from_bodies([develop(g) for g in genomes], seeds=range(N_RANDOM))
    state, rec = simulate(batch, batch.initial_state(), 600, DANCER_ENGINE)  # 10 s
    assert rec is not None
    return batch, rec.positions.astype(np.float64), state


def test_random_genomes_never_blow_up(random_crowd: tuple[BodyBatch, np.ndarray, SimState]) -> None:
    _, _, state = random_crowd
    assert not state.failed.any()


def test_random_genomes_stand_upright(random_crowd: tuple[BodyBatch, np.ndarray, SimState]) -> None:
    batch, pos, _ = random_crowd
    head, pelvis = pos[:, :, idx("head")], pos[:, :, idx("pelvis")]
    feet = pos[:, :, [idx("l_foot"), idx("r_foot")]]
    standing = batch.rest[:, idx("head"), 1]
    # the head stays high: at least 80 % of its standing height in every frame
    assert np.all(head[..., 1] > 0.8 * standing)
    # head over pelvis over feet, in every frame
    assert np.all(head[..., 1] > pelvis[..., 1] + 0.2)
    assert np.all(pelvis[..., 1] > feet[..., 1].max(axis=-1) + 0.3)
    # upright: the head is over the feet, within a quarter of the standing height
    lean = np.abs(head[..., 0] - feet[..., 0].mean(axis=-1))
    assert np.all(lean < 0.25 * standing)
    # and the feet stay on the floor
    assert np.all(feet[-1, :, :, 1] < 0.1)


def test_random_genomes_keep_their_shape(
    random_crowd: tuple[BodyBatch, np.ndarray, SimState],
) -> None:
    batch, pos, _ = random_crowd
    edges = batch.edges[0]
    length = np.linalg.norm(pos[:, :, edges[:, 1]] - pos[:, :, edges[:, 0]], axis=-1)
    error = np.abs(length - batch.rest_length[None])
    # no spring collapses or stretches by more than half its ideal length (or 5 cm)
    assert np.all(error < np.maximum(0.5 * batch.rest_length[None], 0.05))
    # the left side stays left of the right side (no body turned inside out)
    for left, right in (("l_shoulder", "r_shoulder"), ("l_hip", "r_hip")):
        assert np.all(pos[:, :, idx(left), 0] < pos[:, :, idx(right), 0])
