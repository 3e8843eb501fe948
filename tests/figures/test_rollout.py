"""Batched rollout: determinism, batch-size and thread independence, failures, trajectories."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import numpy.typing as npt
import pytest

pytest.importorskip("mujoco")

from sinews.control import HoldPose
from sinews.control.springnet import SpringNetController, SpringNetGenome
from sinews.figures import Figure, LuxoShape, RolloutResult, luxo, rollout, snake
from sinews.figures.mjcf import Servo
from sinews.trajectory import Trajectory

SECONDS = 0.6


@pytest.fixture(scope="module")
def lamp() -> Figure:
    return luxo()


@pytest.fixture(scope="module")
def genome() -> SpringNetGenome:
    return SpringNetGenome.random(np.random.default_rng(7), 33, 4)


@pytest.fixture(scope="module")
def weights(lamp: Figure, genome: SpringNetGenome) -> npt.NDArray[np.float64]:
    """(33, n, S) sensor-to-force weights, one set per net."""
    shape = (genome.n_individuals, genome.n_masses, lamp.n_sensors)
    return np.random.default_rng(3).normal(0.0, 0.5, shape)


def _run(
    figure: Figure,
    genome: SpringNetGenome,
    weights: npt.NDArray[np.float64] | None = None,
    nthread: int | None = None,
) -> RolloutResult:
    controller = SpringNetController(
        genome,
        outputs=np.arange(figure.n_actuators) % genome.n_masses,
        gain=1.2,
        offset=figure.neutral,
        input_weights=weights,
    )
    n = genome.n_individuals
    return rollout(figure, controller, n, SECONDS, record=True, nthread=nthread)


def _assert_rows_equal(a: RolloutResult, rows_a: npt.ArrayLike, b: RolloutResult) -> None:
    rows = np.asarray(rows_a)
    np.testing.assert_array_equal(a.final_x[rows], b.final_x)
    np.testing.assert_array_equal(a.failed[rows], b.failed)
    assert a.qpos is not None and b.qpos is not None
    assert a.body_pos is not None and b.body_pos is not None
    np.testing.assert_array_equal(a.qpos[:, rows], b.qpos)
    np.testing.assert_array_equal(a.body_pos[:, rows], b.body_pos)


def test_spring_nets_make_the_lamp_move(lamp: Figure, genome: SpringNetGenome) -> None:
    result = _run(lamp, genome)
    assert not result.failed.any()
    assert result.qpos is not None
    assert np.ptp(result.qpos[:, :, 3:], axis=0).max() > 0.3  # the joints swing


def test_two_runs_are_bit_identical(
    lamp: Figure, genome: SpringNetGenome, weights: npt.NDArray[np.float64]
) -> None:
    rows = list(range(8))
    first = _run(lamp, genome.take(rows), weights[rows])
    _assert_rows_equal(first, rows, _run(lamp, genome.take(rows), weights[rows]))


@pytest.mark.parametrize("closed_loop", [False, True])
def test_a_row_does_not_depend_on_the_batch_size(
    lamp: Figure, genome: SpringNetGenome, weights: npt.NDArray[np.float64], closed_loop: bool
) -> None:
    full = _run(lamp, genome, weights if closed_loop else None)
    for rows in ([5], list(range(8))):
        alone = _run(lamp, genome.take(rows), weights[rows] if closed_loop else None)
        _assert_rows_equal(full, rows, alone)


def test_thread_count_does_not_change_results(genome: SpringNetGenome) -> None:
    figure = snake()
    few = genome.take(range(6))
    one, two = _run(figure, few, nthread=1), _run(figure, few, nthread=2)
    _assert_rows_equal(one, np.arange(6), two)


class NanForOne:
    """Neutral targets, but NaN for one row from ``at`` seconds on."""

    def __init__(self, figure: Figure, row: int | None, at: float) -> None:
        self.inner = HoldPose(figure.neutral)
        self.row, self.at = row, at

    def reset(self, n_individuals: int) -> None:
        self.inner.reset(n_individuals)

    def control(self, t: float, sensors: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
        out = self.inner.control(t, sensors).copy()
        out[:, 0] += 0.3 * np.sin(6 * t)
        if self.row is not None and t >= self.at:
            out[self.row] = np.nan
        return out


def test_a_nan_target_fails_only_its_row(lamp: Figure) -> None:
    bad = rollout(lamp, NanForOne(lamp, 2, at=0.25), 4, SECONDS, record=True)
    good = rollout(lamp, NanForOne(lamp, None, at=0.25), 4, SECONDS, record=True)
    assert bad.failed.tolist() == [False, False, True, False]
    assert bad.fail_time[2] == pytest.approx(0.25)
    assert np.isnan(bad.fail_time[[0, 1, 3]]).all()
    _assert_rows_equal(good, [0, 1, 3], _subset(bad, [0, 1, 3]))
    assert bad.qpos is not None and np.isfinite(bad.qpos).all()
    frozen = bad.qpos[-1, 2]
    np.testing.assert_array_equal(bad.qpos[-5:, 2], np.broadcast_to(frozen, (5, len(frozen))))


def test_an_exploding_servo_fails_only_its_row() -> None:
    base, elbow, _ = LuxoShape().servos
    stiff = luxo(LuxoShape(servos=(base, elbow, Servo("neck", kp=3e3, kv=0.0, torque=1e9))))
    calm = np.tile(stiff.neutral, (4, 1))
    wild = calm.copy()
    wild[1, 2] = 1.2
    exploded = rollout(stiff, HoldPose(wild), 4, SECONDS)
    reference = rollout(stiff, HoldPose(calm), 4, SECONDS)
    assert exploded.failed.tolist() == [False, True, False, False]
    assert not reference.failed.any()
    np.testing.assert_array_equal(exploded.final_x[[0, 2, 3]], reference.final_x[[0, 2, 3]])
    assert np.isfinite(exploded.final_x).all()


def _subset(result: RolloutResult, rows: list[int]) -> RolloutResult:
    assert result.qpos is not None and result.body_pos is not None
    return RolloutResult(
        figure=result.figure,
        initial_x=result.initial_x[rows],
        final_x=result.final_x[rows],
        failed=result.failed[rows],
        fail_time=result.fail_time[rows],
        record_hz=result.record_hz,
        frame_time=result.frame_time,
        qpos=result.qpos[:, rows],
        body_pos=result.body_pos[:, rows],
    )


def test_recording_converts_to_trajectories(lamp: Figure, tmp_path: Path) -> None:
    result = rollout(lamp, HoldPose(lamp.neutral), 3, 1.0, record=True, record_hz=60)
    assert result.qpos is not None and result.body_pos is not None
    assert result.frame_time is not None
    assert result.qpos.shape == (61, 3, 6)
    assert result.body_pos.shape == (61, 3, 4, 3)
    np.testing.assert_allclose(result.frame_time, np.arange(61) / 60, atol=0.5e-3)
    model = lamp.model()
    np.testing.assert_allclose(result.body_pos[0, 0, :, 2], [0.02, 0.04, 0.2426, 0.3959], atol=1e-3)
    np.testing.assert_array_equal(result.qpos[0, 0], model.qpos0)
    trajectories = result.trajectories()
    assert len(trajectories) == 3
    traj = trajectories[1]
    assert isinstance(traj, Trajectory)
    assert traj.fps == 60 and traj.n_frames == 61 and traj.n_nodes == 4
    assert traj.node_names == lamp.body_names
    np.testing.assert_array_equal(traj.edges, lamp.edges)
    np.testing.assert_array_equal(traj.positions, result.body_pos[:, 1][:, :, [0, 2]])
    assert traj.qpos is not None and traj.qpos.shape == (61, 6)
    loaded = Trajectory.load(traj.save(tmp_path / "lamp.npz"))
    np.testing.assert_array_equal(loaded.positions, traj.positions)
    assert loaded.body_pos is not None and loaded.body_pos.shape == (61, 4, 3)
    assert not loaded.failed


def test_unrecorded_rollout_has_no_trajectory(lamp: Figure) -> None:
    result = rollout(lamp, HoldPose(lamp.neutral), 2, 0.1)
    assert result.qpos is None
    with pytest.raises(ValueError, match="record=True"):
        result.trajectory(0)


def test_rollout_checks_its_arguments(lamp: Figure) -> None:
    hold = HoldPose(lamp.neutral)
    with pytest.raises(ValueError, match="control_hz"):
        rollout(lamp, hold, 2, 0.1, control_hz=300)
    with pytest.raises(ValueError, match="n_individuals"):
        rollout(lamp, hold, 0, 0.1)
    with pytest.raises(ValueError, match="answered shape"):
        rollout(lamp, HoldPose(np.zeros(2)), 2, 0.1)
