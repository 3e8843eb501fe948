"""Physical sanity of the built-in figures: resting poses, contact forces, servo tracking."""

from __future__ import annotations

import numpy as np
import numpy.typing as npt
import pytest

pytest.importorskip("mujoco")

from sinews.control import HoldPose
from sinews.figures import Figure, humanoid, luxo, rollout, snake

G = 9.81


class Recording:
    """Wraps a controller and keeps each tick's time and sensors."""

    def __init__(self, inner: HoldPose | StepTarget) -> None:
        self.inner = inner
        self.times: list[float] = []
        self.sensors: list[npt.NDArray[np.float64]] = []

    def reset(self, n_individuals: int) -> None:
        self.times.clear()
        self.sensors.clear()
        self.inner.reset(n_individuals)

    def control(self, t: float, sensors: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
        self.times.append(t)
        self.sensors.append(sensors.copy())
        return self.inner.control(t, sensors)

    def column(self, figure: Figure, name: str) -> npt.NDArray[np.float64]:
        """(ticks, P) one sensor column over time."""
        return np.stack(self.sensors)[:, :, figure.sensor_index(name)]


class StepTarget:
    """Neutral targets, then ``delta`` added to joint ``joint`` from ``at`` seconds on."""

    def __init__(self, figure: Figure, joint: int, delta: float, at: float) -> None:
        self.before = figure.neutral.copy()
        self.after = figure.neutral.copy()
        self.after[joint] += delta
        self.at = at
        self.n = 1

    def reset(self, n_individuals: int) -> None:
        self.n = n_individuals

    def control(self, t: float, sensors: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
        target = self.after if t >= self.at else self.before
        return np.tile(target, (self.n, 1))


def _weight(figure: Figure) -> float:
    return float(figure.model().body_subtreemass[1]) * G


def test_lamp_stands_upright_on_its_base_for_two_seconds() -> None:
    figure = luxo()
    probe = Recording(HoldPose(figure.neutral))
    result = rollout(figure, probe, 2, 2.0, record=True, record_hz=20)
    assert not result.failed.any()
    pitch = probe.column(figure, "root_pitch")
    assert np.abs(pitch).max() < 0.01
    assert np.abs(probe.column(figure, "root_z")).max() < 0.005
    assert np.abs(result.distance).max() < 0.005
    angles = np.stack(probe.sensors)[-1][:, 4:7]
    assert np.abs(angles - figure.neutral).max() < 0.1  # droop under gravity only
    settled = slice(len(probe.times) // 2, None)
    fz_base = probe.column(figure, "fz_base")[settled]
    np.testing.assert_allclose(fz_base, _weight(figure), rtol=0.02)
    assert np.abs(probe.column(figure, "fx_base")[settled]).max() < 0.05 * _weight(figure)
    assert (probe.column(figure, "fz_head") == 0).all()
    head = figure.body_names.index("head")
    assert result.body_pos is not None
    assert result.body_pos[:, :, head, 2].min() > 0.3  # head stays up


def test_humanoid_stands_for_a_moment() -> None:
    figure = humanoid()
    probe = Recording(HoldPose(figure.neutral))
    result = rollout(figure, probe, 1, 1.0, record=True, record_hz=20)
    assert not result.failed.any()
    assert result.body_pos is not None
    head = figure.body_names.index("head")
    assert result.body_pos[:, 0, head, 2].min() > 1.45
    assert np.abs(probe.column(figure, "root_pitch")).max() < 0.05
    feet = probe.column(figure, "fz_foot_l") + probe.column(figure, "fz_foot_r")
    np.testing.assert_allclose(feet[len(feet) // 2 :], _weight(figure), rtol=0.05)


def test_snake_lies_on_the_ground() -> None:
    figure = snake()
    probe = Recording(HoldPose(figure.neutral))
    result = rollout(figure, probe, 1, 1.0)
    assert not result.failed.any()
    radius = 0.03
    np.testing.assert_allclose(probe.column(figure, "root_z")[-1], 0.0, atol=0.002)
    assert result.figure.model().body("middle").pos[2] == pytest.approx(radius)
    support = sum(probe.column(figure, f"fz_{b}")[-1] for b in ("tail", "middle", "head"))
    np.testing.assert_allclose(support, _weight(figure), rtol=0.02)


@pytest.mark.parametrize(("joint", "delta"), [(1, 0.4), (2, -0.5)])
def test_pd_servo_tracks_a_step_target(joint: int, delta: float) -> None:
    figure = luxo()
    probe = Recording(StepTarget(figure, joint, delta, at=0.3))
    result = rollout(figure, probe, 1, 1.5)
    assert not result.failed.any()
    angle = probe.column(figure, f"q_{figure.joints[joint]}")[:, 0]
    times = np.array(probe.times)
    before = angle[(times > 0.2) & (times < 0.3)]
    after = angle[times > 1.2]
    assert np.abs(before - figure.neutral[joint]).max() < 0.05
    assert np.abs(after - (figure.neutral[joint] + delta)).max() < 0.05
    halfway = times[np.argmax(np.abs(angle - figure.neutral[joint]) > abs(delta) / 2)]
    assert 0.3 < halfway < 0.5  # responds within ~0.2 s
