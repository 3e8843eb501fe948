"""The frame loop: hand-computed cases, physical behaviour, reference agreement, health."""

from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np
import pytest

from sinews.springmass import (
    Backend,
    Body,
    BodyBatch,
    BodyError,
    EngineParams,
    Recording,
    SimState,
    Status,
    engine,
    simulate,
)

FREE = EngineParams(dt=0.01, gravity=0.0, floor=False)


def two_nodes(**kwargs: Any) -> Body:
    """Two nodes joined by a stretched spring; ``kwargs`` go to `Body.build`."""
    options: dict[str, Any] = {"mass": [1.0, 2.0], "strength": [50.0], "rest_length": [1.0]}
    options.update(kwargs)
    return Body.build(["a", "b"], [[0.0, 0.0], [1.5, 0.0]], [(0, 1)], **options)


def run(
    body: Body, steps: int, params: EngineParams = FREE, **kwargs: Any
) -> tuple[SimState, Recording | None]:
    """``body`` alone for ``steps`` frames; ``kwargs`` go to `simulate`."""
    batch = BodyBatch.from_bodies([body])
    return simulate(batch, batch.initial_state(), steps, params, **kwargs)


@pytest.mark.parametrize("backend", ["numba", "numpy"])
def test_one_frame_matches_hand_computation(backend: Backend) -> None:
    # spring stretched by 0.5: force 50 * 0.5 = 25 N pulls a (+x) and b (-x)
    body = two_nodes(weight=[1.0, 1.0], drag=0.1)
    params = EngineParams(dt=0.01, gravity=10.0, floor=False)
    state, rec = run(body, 1, params, backend=backend)
    # a: F = (25, -10) / 1 kg; b: F = (-25, -20) / 2 kg
    va = np.array([25.0, -10.0]) * 0.01
    vb = np.array([-25.0, -20.0]) / 2.0 * 0.01
    xa = np.array([0.0, 0.0]) + va * 0.01
    xb = np.array([1.5, 0.0]) + vb * 0.01
    np.testing.assert_allclose(state.positions[0], [xa, xb], rtol=0, atol=1e-6)
    np.testing.assert_allclose(state.velocities[0], [va * 0.9, vb * 0.9], rtol=0, atol=1e-9)
    assert rec is not None and rec.positions.shape == (2, 1, 2, 2)


def test_undamped_spring_conserves_energy_without_drift() -> None:
    body = two_nodes(drag=0.0)
    batch = BodyBatch.from_bodies([body])
    state, rec = simulate(batch, batch.initial_state(), 20_000, FREE)
    assert rec is not None
    pos = rec.positions[:, 0].astype(np.float64)
    vel = np.diff(pos, axis=0) / FREE.dt
    length = np.linalg.norm(pos[1:, 1] - pos[1:, 0], axis=1)
    energy = 0.5 * (vel[:, 0] ** 2).sum(1) + 0.5 * 2.0 * (vel[:, 1] ** 2).sum(1)
    energy += 0.5 * 50.0 * (length - 1.0) ** 2
    start = 0.5 * 50.0 * 0.5**2
    # symplectic Euler: bounded oscillation around the true energy, no secular drift
    assert np.all(np.abs(energy - start) < 0.1 * start)
    first, last = energy[:2000].mean(), energy[-2000:].mean()
    assert abs(last - first) < 0.005 * start
    assert not state.failed.any()


def test_drag_scales_velocity_each_step() -> None:
    body = Body.build(["a"], [[0.0, 0.0]], [], drag=0.25)
    batch = BodyBatch.from_bodies([body])
    state = batch.initial_state()
    state.velocities[0, 0] = [4.0, 0.0]
    state, _ = simulate(batch, state, 3, FREE)
    assert state.velocities[0, 0, 0] == pytest.approx(4.0 * 0.75**3)


def test_easing_removes_its_fraction_of_the_length_error() -> None:
    body = two_nodes(strength=[0.0], easing=[0.5])
    state, _ = run(body, 1)
    length = np.linalg.norm(state.positions[0, 1] - state.positions[0, 0])
    assert length == pytest.approx(1.5 - 0.5 * 0.5, abs=1e-9)  # error 0.5 halved
    assert np.allclose(state.velocities, 0.0)  # easing moves positions only


def test_negative_weight_rises_and_zero_weight_floats() -> None:
    body = Body.build(["balloon", "dust", "stone"], [[0, 1], [1, 1], [2, 1]], [],
                      weight=[-0.5, 0.0, 1.0])  # fmt: skip
    params = EngineParams(dt=0.01, gravity=9.81, floor=False)
    state, _ = run(body, 100, params)
    y = state.positions[0, :, 1]
    assert y[0] > 1.0 and y[1] == 1.0 and y[2] < 1.0
    assert (y[0] - 1.0) == pytest.approx(0.5 * (1.0 - y[2]), rel=1e-9)


def test_attraction_pulls_only_the_attracted_node_and_only_within_reach() -> None:
    def pair(distance: float) -> Body:
        rest = [[0.0, 0.0], [distance, 0.0]]
        return Body.build(["hand", "other"], rest, [], attraction=[(0, 1)],
                          attraction_strength=[5.0], attraction_reach=[2.0])  # fmt: skip

    near, far = pair(1.0), pair(3.0)
    state, _ = run(near, 10)
    assert state.positions[0, 0, 0] > 0.0  # hand moved toward the other
    assert state.positions[0, 1, 0] == 1.0  # one-directional
    state, _ = run(far, 10)
    assert state.positions[0, 0, 0] == 0.0


def test_floor_holds_nodes_at_their_radius() -> None:
    body = Body.build(["a"], [[0.0, 1.0]], [], radius=[0.1])
    state, _ = run(body, 300, EngineParams(dt=0.01))
    assert state.positions[0, 0, 1] == pytest.approx(0.1)


def test_external_forces_per_step_and_constant() -> None:
    body = Body.build(["a"], [[0.0, 0.0]], [], drag=0.0)
    push = np.zeros((1, 1, 2))
    push[0, 0] = [2.0, 0.0]
    constant, _ = run(body, 5, external=push)
    per_step, _ = run(body, 5, external=np.repeat(push[None], 5, axis=0))
    np.testing.assert_array_equal(constant.positions, per_step.positions)
    assert constant.velocities[0, 0, 0] == pytest.approx(2.0 * 0.01 * 5)
    with pytest.raises(BodyError, match="external forces"):
        run(body, 5, external=np.zeros((3, 1, 1, 2)))


def test_pose_signals_move_the_home_target() -> None:
    # one node held by home: it settles where the pose moves its target, and back after
    body = Body.build(["a"], [[0.0, 1.0]], [], home=[400.0], drag=0.2,
                      pose_basis=[[[0.1, 0.0], [0.0, -0.05]]])  # fmt: skip
    pose = np.tile([2.0, 1.0], (300, 1))
    moved, _ = run(body, 300, pose=pose)
    np.testing.assert_allclose(moved.positions[0, 0], [0.2, 0.95], atol=1e-6)
    back, _ = run(body, 600, pose=pose)
    np.testing.assert_allclose(back.positions[0, 0], [0.0, 1.0], atol=1e-6)
    with pytest.raises(BodyError, match="pose must have shape"):
        run(body, 5, pose=np.zeros((5, 3)))
    with pytest.raises(BodyError, match="pose_basis must have shape"):
        Body.build(["a"], [[0.0, 0.0]], [], pose_basis=np.zeros((2, 1, 2)))


def random_body(rng: np.random.Generator, n: int) -> Body:
    n_edges = int(rng.integers(1, 3 * n))
    edges: list[tuple[int, int]] = []
    while len(edges) < n_edges:
        i, j = rng.integers(0, n, 2)
        if i != j:
            edges.append((int(i), int(j)))
    return Body.build(
        [f"n{k}" for k in range(n)],
        rng.uniform(0, 1, (n, 2)) + np.array([0.0, 0.3]),
        edges,
        mass=rng.uniform(0.5, 2.0, n),
        weight=rng.uniform(-1.0, 1.0, n),
        radius=rng.uniform(0.0, 0.05, n),
        strength=rng.uniform(5.0, 300.0, n_edges),
        rest_length=rng.uniform(0.2, 1.2, n_edges),
        easing=rng.uniform(0.0, 0.3, n_edges) * (rng.random(n_edges) < 0.5),
        home=rng.uniform(0.0, 60.0, n),
        wiggle=rng.uniform(0.0, 8.0, n) * (rng.random(n) < 0.7),
        drag=float(rng.uniform(0.0, 0.05)),
        attraction=[(0, n - 1)],
        attraction_strength=[rng.uniform(1.0, 10.0)],
        attraction_reach=[rng.uniform(0.1, 2.0)],
    )


@pytest.mark.parametrize("follow", [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0)])
def test_numba_kernel_agrees_with_numpy_reference(follow: tuple[float, float]) -> None:
    rng = np.random.default_rng(7)
    bodies = [random_body(rng, int(rng.integers(2, 15))) for _ in range(12)]
    # most bodies move their home targets by two pose signals (the last rows have none)
    bodies = [
        dataclasses.replace(b, pose_basis=rng.normal(0.0, 0.1, (b.n_nodes, 2, 2))) if k % 3 else b
        for k, b in enumerate(bodies)
    ]
    batch = BodyBatch.from_bodies(bodies, seeds=rng.integers(0, 2**63, 12).tolist())
    params = EngineParams(home_follow=follow, restitution=0.3)
    push = rng.normal(0.0, 5.0, (200, *batch.rest.shape))
    pose = rng.normal(0.0, 1.0, (150, 2))
    results = [
        simulate(
            batch,
            batch.initial_state(),
            200,
            params,
            external=push,
            pose=pose,
            backend=b,
            record_stride=3,
            record_forces=True,
        )
        for b in ("numba", "numpy")
    ]
    (fast, fast_rec), (ref, ref_rec) = results
    assert fast_rec is not None and ref_rec is not None
    np.testing.assert_allclose(fast.positions, ref.positions, rtol=0, atol=1e-9)
    np.testing.assert_allclose(fast.velocities, ref.velocities, rtol=0, atol=1e-9)
    np.testing.assert_allclose(fast_rec.positions, ref_rec.positions, rtol=0, atol=1e-5)
    assert fast_rec.forces is not None and ref_rec.forces is not None
    np.testing.assert_allclose(fast_rec.forces, ref_rec.forces, rtol=1e-5, atol=1e-4)
    np.testing.assert_array_equal(fast.status, ref.status)


def test_motion_is_bit_identical_across_runs_and_batch_sizes() -> None:
    rng = np.random.default_rng(3)
    bodies = [random_body(rng, int(rng.integers(2, 15))) for _ in range(9)]
    seeds = list(range(100, 109))
    big = BodyBatch.from_bodies(bodies, seeds=seeds)
    params = EngineParams(home_follow=(1.0, 0.0))
    first, rec1 = simulate(big, big.initial_state(), 300, params)
    second, rec2 = simulate(big, big.initial_state(), 300, params)
    np.testing.assert_array_equal(first.positions, second.positions)
    assert rec1 is not None and rec2 is not None
    np.testing.assert_array_equal(rec1.positions, rec2.positions)
    for k in (0, 4, 8):
        alone = BodyBatch.from_bodies([bodies[k]], seeds=[seeds[k]])
        solo, _ = simulate(alone, alone.initial_state(), 300, params)
        n = bodies[k].n_nodes
        np.testing.assert_array_equal(solo.positions[0, :n], first.positions[k, :n])


def test_stepping_in_pieces_equals_one_run() -> None:
    rng = np.random.default_rng(4)
    batch = BodyBatch.from_bodies([random_body(rng, 8)], seeds=[9])
    whole, _ = simulate(batch, batch.initial_state(), 100)
    state = batch.initial_state()
    for _ in range(4):
        state, _ = simulate(batch, state, 25)
    np.testing.assert_array_equal(whole.positions, state.positions)
    assert state.step == 100


def test_wiggle_depends_on_the_seed() -> None:
    body = Body.build(["a"], [[0.0, 0.0]], [], wiggle=[3.0])
    batch = BodyBatch.from_bodies([body, body, body], seeds=[1, 1, 2])
    state, _ = simulate(batch, batch.initial_state(), 60, FREE)
    np.testing.assert_array_equal(state.positions[0], state.positions[1])
    assert not np.array_equal(state.positions[0], state.positions[2])
    assert np.abs(state.positions[0]).max() > 0


@pytest.mark.parametrize("backend", ["numba", "numpy"])
def test_a_blown_up_body_is_flagged_frozen_and_does_not_touch_the_others(backend: Backend) -> None:
    rng = np.random.default_rng(5)
    calm = [random_body(rng, 6) for _ in range(3)]
    # a stiff spring on a light node at a big step explodes
    wild = Body.build(["a", "b"], [[0.0, 1.0], [0.5, 1.0]], [(0, 1)], mass=[1e-3, 1e-3],
                      strength=[1e6], rest_length=[0.1])  # fmt: skip
    params = EngineParams(max_speed=50.0)
    mixed = BodyBatch.from_bodies([calm[0], wild, calm[1], calm[2]], seeds=[0, 1, 2, 3])
    state, rec = simulate(mixed, mixed.initial_state(), 120, params, backend=backend)
    alone = BodyBatch.from_bodies(calm, seeds=[0, 2, 3])
    ref, _ = simulate(alone, alone.initial_state(), 120, params, backend=backend)
    assert list(state.status) == [Status.OK, Status.RUNAWAY, Status.OK, Status.OK]
    assert state.failed_step[1] >= 0
    assert np.isfinite(state.positions).all() and rec is not None
    assert np.isfinite(rec.positions).all()
    frozen = rec.positions[state.failed_step[1] + 1 :, 1, :2]
    assert np.all(frozen == frozen[0])
    for k, p in enumerate([0, 2, 3]):
        n = calm[k].n_nodes
        np.testing.assert_array_equal(state.positions[p, :n], ref.positions[k, :n])


def test_non_finite_external_force_marks_non_finite() -> None:
    body = Body.build(["a"], [[0.0, 0.0]], [])
    push = np.full((1, 1, 2), np.nan)
    state, rec = run(body, 10, external=push)
    assert state.status[0] == Status.NON_FINITE and state.failed_step[0] == 0
    assert rec is not None and np.all(rec.positions == 0.0)


def test_recording_stride_and_trajectory() -> None:
    rng = np.random.default_rng(8)
    bodies = [random_body(rng, 4), random_body(rng, 9)]
    batch = BodyBatch.from_bodies(bodies)
    state, rec = simulate(batch, batch.initial_state(), 12, record_stride=4)
    assert rec is not None
    assert rec.positions.shape == (4, 2, 9, 2) and rec.fps == pytest.approx(15.0)
    traj = rec.trajectory(batch, state, 0)
    assert traj.positions.shape == (4, 4, 2) and traj.node_names == bodies[0].names
    np.testing.assert_array_equal(traj.positions[-1], state.positions[0, :4].astype(np.float32))


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"mass": [1.0, 0.0]}, "mass"),
        ({"strength": [-1.0]}, "strength"),
        ({"easing": [1.5]}, "easing"),
        ({"rest_length": [0.0]}, "rest_length"),
        ({"radius": [np.nan, 0.1]}, "radius"),
        ({"drag": 1.0}, "drag"),
        ({"attraction": [(0, 5)], "attraction_strength": [1.0], "attraction_reach": [1.0]},
         "attraction"),
    ],
)  # fmt: skip
def test_bad_bodies_are_rejected_with_a_reason(kwargs: dict[str, object], message: str) -> None:
    with pytest.raises(BodyError, match=message):
        two_nodes(**kwargs)


def test_bad_edges_and_names() -> None:
    with pytest.raises(BodyError, match="different nodes"):
        Body.build(["a", "b"], [[0, 0], [1, 0]], [(1, 1)])
    with pytest.raises(BodyError, match="unique"):
        Body.build(["a", "a"], [[0, 0], [1, 0]], [(0, 1)])
    with pytest.raises(BodyError, match="home_follow"):
        EngineParams(home_follow=(2.0, 0.0))


def test_small_and_large_batches_give_the_same_motion_bit_for_bit(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """Batches up to SERIAL_BODIES run on the serial kernel, larger ones on the threaded one:
    the same bodies move identically either way."""
    rng = np.random.default_rng(11)
    bodies = [random_body(rng, int(rng.integers(2, 15))) for _ in range(9)]
    batch = BodyBatch.from_bodies(bodies, seeds=rng.integers(0, 2**63, 9).tolist())
    push = rng.normal(0.0, 5.0, (120, *batch.rest.shape))
    runs = []
    for serial_bodies in (0, 9):  # threaded, then serial
        monkeypatch.setattr(engine, "SERIAL_BODIES", serial_bodies)
        runs.append(simulate(batch, batch.initial_state(), 120, external=push, record_forces=True))
    (threaded, by_threads), (serial, by_one) = runs
    assert by_threads is not None and by_one is not None
    np.testing.assert_array_equal(threaded.positions, serial.positions)
    np.testing.assert_array_equal(threaded.velocities, serial.velocities)
    np.testing.assert_array_equal(by_threads.positions, by_one.positions)
    assert by_threads.forces is not None and by_one.forces is not None
    np.testing.assert_array_equal(by_threads.forces, by_one.forces)
