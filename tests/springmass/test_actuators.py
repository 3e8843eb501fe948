"""Actuators: each force pattern, channel isolation, and agreement with the reference."""

from __future__ import annotations

import numpy as np
import pytest

from sinews.springmass import Body, BodyBatch, BodyError, EngineParams, simulate
from sinews.springmass.actuators import ActuatorKind

FREE = EngineParams(dt=0.01, gravity=0.0, floor=False)


def one_node(kind: ActuatorKind, custom: float, channels: tuple[int, int] = (0, 0)) -> Body:
    # a second, heavy node left of the first sets the centroid
    return Body.build(
        ["hand", "anchor"], [[1.0, 0.0], [-1.0, 0.0]], [], mass=[1.0, 1e9], drag=0.0,
        actuator_node=[0], actuator_kind=[kind], actuator_channels=[channels],
        actuator_strength=[10.0], actuator_custom=[custom],
    )  # fmt: skip


def first_velocity(body: Body, drive: np.ndarray, phase: np.ndarray | None = None) -> np.ndarray:
    batch = BodyBatch.from_bodies([body])
    state, _ = simulate(batch, batch.initial_state(), 1, FREE, drive=drive, phase=phase)
    return state.velocities[0, 0] / (10.0 * FREE.dt)  # direction and drive


@pytest.mark.parametrize(
    ("kind", "custom", "expected"),
    [
        (ActuatorKind.PUSH, 0.25, [0.0, 1.0]),  # a kick straight up
        (ActuatorKind.PUSH, 0.5, [-1.0, 0.0]),
        (ActuatorKind.SPIN, 0.9, [0.0, 1.0]),  # counter-clockwise about the centroid
        (ActuatorKind.SPIN, 0.1, [0.0, -1.0]),
        (ActuatorKind.REACH, 0.0, [1.0, 0.0]),  # outward from the centroid
        (ActuatorKind.REACH, 1.0, [0.0, 1.0]),  # straight up
    ],
)
def test_point_actuators_push_the_way_they_say(
    kind: ActuatorKind, custom: float, expected: list[float]
) -> None:
    velocity = first_velocity(one_node(kind, custom), np.ones((1, 1)))
    np.testing.assert_allclose(velocity, expected, atol=1e-6)


def test_bounce_squashes_while_fresh_then_lifts() -> None:
    body = one_node(ActuatorKind.BOB, 0.0)  # the first 15 % of the decay is the squash
    assert first_velocity(body, np.array([[1.0]]))[1] == pytest.approx(-1.0)
    assert first_velocity(body, np.array([[0.5]]))[1] == pytest.approx(0.5)


def test_sway_follows_the_phase_and_shake_oscillates() -> None:
    body = one_node(ActuatorKind.SWAY, 0.0)
    on_beat = first_velocity(body, np.ones((1, 1)), phase=np.array([0.0]))
    half = first_velocity(body, np.ones((1, 1)), phase=np.array([0.5]))
    assert on_beat[0] == pytest.approx(1.0) and half[0] == pytest.approx(-1.0)
    mirrored = first_velocity(one_node(ActuatorKind.SWAY, 0.7), np.ones((1, 1)), phase=np.zeros(1))
    assert mirrored[0] == pytest.approx(-1.0)
    # shake: two cycles per phase cycle (dancers: one per beat), sideways for custom 0
    phase = np.arange(120) / 120.0
    shaker = BodyBatch.from_bodies([one_node(ActuatorKind.SHAKE, 0.0)])
    _, rec = simulate(
        shaker, shaker.initial_state(), 120, FREE, drive=np.ones((120, 1)), phase=phase
    )
    assert rec is not None
    x = rec.positions[:, 0, 0, 0]
    turns = np.sum(np.diff(np.sign(np.diff(x))) != 0)
    assert np.ptp(x) > 0 and turns >= 3  # back and forth, twice
    upright = first_velocity(one_node(ActuatorKind.SHAKE, 1.0), np.ones((1, 1)), phase=np.zeros(1))
    assert upright[0] == pytest.approx(0.0, abs=1e-9) and upright[1] == pytest.approx(1.0)


def test_pulse_pushes_neighbours_away_and_conserves_momentum() -> None:
    body = Body.build(
        ["centre", "left", "right", "far"], [[0, 0], [-1, 0], [1, 0], [5, 0]],
        [(0, 1), (2, 0)], strength=[0.0, 0.0], drag=0.0,
        actuator_node=[0], actuator_kind=[ActuatorKind.PULSE], actuator_channels=[(0, 0)],
        actuator_strength=[4.0], actuator_custom=[1.0],
    )  # fmt: skip
    batch = BodyBatch.from_bodies([body])
    state, _ = simulate(batch, batch.initial_state(), 1, FREE, drive=np.ones((1, 1)))
    v = state.velocities[0]
    assert v[1, 0] < 0 < v[2, 0] and np.all(v[3] == 0)
    np.testing.assert_allclose(v.sum(axis=0), 0.0, atol=1e-12)


def test_an_actuator_never_reacts_to_channels_outside_its_range() -> None:
    body = one_node(ActuatorKind.PUSH, 0.0, channels=(2, 3))
    batch = BodyBatch.from_bodies([body])
    drive = np.zeros((50, 6))
    drive[:, [0, 1, 4, 5]] = 1.0
    quiet, _ = simulate(batch, batch.initial_state(), 50, FREE, drive=drive)
    assert np.all(quiet.velocities == 0)
    drive[:, 3] = 0.5
    loud, _ = simulate(batch, batch.initial_state(), 50, FREE, drive=drive)
    assert loud.velocities[0, 0, 0] > 0


def test_no_drive_after_the_table_ends() -> None:
    body = one_node(ActuatorKind.PUSH, 0.0)
    batch = BodyBatch.from_bodies([body])
    state, _ = simulate(batch, batch.initial_state(), 20, FREE, drive=np.ones((5, 1)))
    assert state.velocities[0, 0, 0] == pytest.approx(5 * 10.0 * FREE.dt)


def test_bad_drive_tables_are_rejected() -> None:
    batch = BodyBatch.from_bodies([one_node(ActuatorKind.PUSH, 0.0, channels=(0, 4))])
    state = batch.initial_state()
    with pytest.raises(BodyError, match="channel 4"):
        simulate(batch, state, 1, FREE, drive=np.ones((3, 2)))
    with pytest.raises(BodyError, match=">= 0"):
        simulate(batch, state, 1, FREE, drive=-np.ones((3, 5)))
    with pytest.raises(BodyError, match="phase"):
        simulate(batch, state, 1, FREE, drive=np.ones((3, 5)), phase=np.zeros(2))
    with pytest.raises(BodyError, match="ActuatorKind"):
        one_node(99, 0.0)  # type: ignore[arg-type]


def test_actuators_agree_with_the_reference() -> None:
    rng = np.random.default_rng(11)
    bodies = []
    for _ in range(6):
        n = int(rng.integers(3, 9))
        n_act = int(rng.integers(1, 8))
        lo = rng.integers(0, 10, n_act)
        bodies.append(
            Body.build(
                [f"n{k}" for k in range(n)], rng.uniform(0, 1, (n, 2)) + np.array([0.0, 0.5]),
                [(k, k + 1) for k in range(n - 1)], home=np.full(n, 20.0),
                actuator_node=rng.integers(0, n, n_act),
                actuator_kind=rng.integers(0, len(ActuatorKind), n_act),
                actuator_channels=np.stack([lo, lo + rng.integers(0, 3, n_act)], axis=1),
                actuator_strength=rng.uniform(0, 30, n_act),
                actuator_custom=rng.uniform(0, 1, n_act),
            )
        )  # fmt: skip
    batch = BodyBatch.from_bodies(bodies, seeds=range(6))
    drive = rng.random((150, 12)) * (rng.random((150, 12)) < 0.2)
    phase = np.arange(150) % 30 / 30.0
    fast, _ = simulate(batch, batch.initial_state(), 150, drive=drive, phase=phase)
    ref, _ = simulate(batch, batch.initial_state(), 150, drive=drive, phase=phase, backend="numpy")
    np.testing.assert_allclose(fast.positions, ref.positions, rtol=0, atol=1e-9)
    assert np.abs(fast.positions - batch.rest).max() > 0.01  # the actuators did move things
