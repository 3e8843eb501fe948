"""The fitness terms of a task, measured for a whole population while it moves.

`TaskMeter` is a rollout observer (``rollout(..., observer=meter)``): every
control tick it reads the (P, S) sensor array and the servo targets, and
afterwards `TaskMeter.terms` gives each individual's term values.

The terms (`TERMS`), each **higher is better** (penalties are ≤ 0), as
`sinews.evolve.fitness` expects:

- ``distance`` (the main goal): minus the tracked point's distance to the
  target at the end, m, or, for a goal with a ``hold``, the farthest it is
  over the trial's last ``hold`` seconds. For a direction goal (pointing),
  minus the angle at the origin between the tracked point and the target
  (at the end, or the largest over the hold), rad; for a
  wave, minus how far the last seconds fall short of the wave, m (the
  missing amplitude at the wave's rate, plus how far the swing's centre
  lies beyond its bound, plus the mean depth below the required height).
- ``early``: 1 − (time from which the tracked point stays within
  ``goal.radius`` to the end) / duration; 0 if it does not end there. "Bonus
  for completing the motion early": a hand that passes through the target
  early and leaves it has not completed the motion. (Counting the first pass,
  the best of a 250 × 30 touch run at full weight was a hand that ended 9.7 cm
  from the point, against 3.4 cm for its last generation's best.)
- ``still``: minus the path length of the tracked point after it first
  arrived, m. "Penalty for excess movement after the goal was met."
- ``head``: minus the fraction of ticks with any contact on a head body.
- ``fallen``: minus the fraction of ticks the figure is down ("falling
  over"): its root tilted beyond ``max_tilt``, lower than ``min_height``,
  the task's ``low`` column under its value (a dancing lamp's shade), or any
  of its limb bodies (a lamp's arms; a person's trunk, arms and legs)
  touching the floor.
- ``neutral``: minus the mean |angle − neutral| of the driven joints at the
  end, rad, leaving out a heading joint (it turns the whole figure). "Bonus
  for ending with joints at neutral angles."
- ``energy``: minus the work of the servos, Σ |τ · q̇| Δt over the ticks, J
  (τ from the PD law and each servo's torque limit); off in the built-ins.
- ``touch``: minus the fraction of ticks with contact on a touch body (the
  limbo pole).
- ``duck``: minus the mean over the trial of how far the top of the figure's surface stands
  above a bar's underside while its root is still before the bar, m (`Task.duck`): the
  step between standing at a limbo bar and passing under it is getting low.

A dance's terms (they need the song's beat times, ``TaskMeter(..., beats=...)``):

- ``lift`` (a dance's main goal): the beat lift of the driven joints' motion
  (`sinews.music.beat_align.beat_lift` with the joint angles as the moving points,
  sampled at the control rate): how much better the motion's pauses fall on the
  beats than on the same beats at other phases. About 0 for motion that ignores
  the beat, however it moves.
- ``spot``: minus the mean distance of the tracked point from the goal over the
  trial, m: a dance's "stay near a spot", a hop's "get there soon".
- ``joints``: minus the mean shortfall of each driven joint's swing (the standard
  deviation of its angle) below `JOINT_SWING`, as a share of it ("use all joints").
- ``smooth``: the driven joints' `sinews.music.beat_align.smoothness` minus 1.
"""

from __future__ import annotations

from collections import deque

import numpy as np
import numpy.typing as npt

from sinews.figures.figure import Figure, FigureError
from sinews.figures.task import TERMS, Task
from sinews.music.beat_align import beat_lift, smoothness

__all__ = ["DANCE_TERMS", "JOINT_SWING", "TERMS", "TaskMeter", "joint_lift"]

DANCE_TERMS = ("lift", "joints", "smooth")
"""The terms measured on the driven joints' whole motion (recorded only when weighed)."""
JOINT_SWING = 0.1
"""A joint swinging less than this (standard deviation of its angle, rad) is under-used."""

FloatArray = npt.NDArray[np.float64]


class TaskMeter:
    """Measures a task's terms for P individuals from a rollout's observations.

    Pass it as ``rollout(..., observer=meter)``; then `terms` gives the
    (P, K) term values in the order of ``task.weights``.

    Args:
        task: the task.
        n_individuals: P.
        beats: (K,) the song's beat times, s (a dance's ``lift`` needs them).
    """

    def __init__(
        self, task: Task, n_individuals: int, *, beats: npt.ArrayLike | None = None
    ) -> None:
        if "lift" in task.weights and beats is None:
            raise FigureError(f"{task.name}: the beat lift needs the song's beats")
        figure = task.figure
        index = figure.sensor_index
        self.task = task
        self._tracked = [index(c) for c in task.goal.tracked]
        target = task.goal.target
        self._moving = np.array([isinstance(t, str) for t in target])
        self._goal_column = [index(t) if isinstance(t, str) else 0 for t in target]
        self._goal_fixed = np.array([0.0 if isinstance(t, str) else float(t) for t in target])
        self._head = _force_columns(figure, figure.head_bodies)
        self._touch = _force_columns(figure, figure.touch_bodies)
        self._limbs = _force_columns(figure, figure.limb_bodies)
        self._root = index("root_z"), index(figure.tilt_column)
        self._low = None if task.low is None else (index(task.low[0]), task.low[1])
        self._q = [index(f"q_{j}") for j in figure.joints]
        self._dq = [index(f"dq_{j}") for j in figure.joints]
        self._driven = task.actuators
        # the pose the neutral bonus looks at: the heading joint says where, not how, it stands
        self._posed = [i for i in task.actuators if figure.joints[i] != figure.heading_joint]
        self._torque = np.abs(figure.model().actuator_forcerange).max(axis=1)
        goal = task.goal
        self._origin = [index(c) for c in goal.origin]
        self._wave = goal.wave
        n = n_individuals
        self._wave_sums = np.zeros((n, 4))  # Σ y·sin, Σ y·cos, Σ depth below, Σ y
        self._wave_basis = np.zeros(2)  # Σ sin, Σ cos
        self._wave_count = 0
        self._count = 0
        self._last_t = 0.0
        self._arrival = np.full(n, np.inf)  # first time within the goal's radius
        self._settled = np.full(n, np.inf)  # since when it has stayed within it
        self._path = np.zeros(n)
        self._previous = np.zeros((n, len(self._tracked)))
        self._distance = np.zeros(n)
        # (time, (P,) distance) of the ticks within ``goal.hold`` of the latest
        self._history: deque[tuple[float, FloatArray]] | None = deque() if goal.hold else None
        self._head_ticks = np.zeros(n)
        self._fallen_ticks = np.zeros(n)
        self._touch_ticks = np.zeros(n)
        self._energy = np.zeros(n)
        self._power = np.zeros(n)
        self._neutral = np.zeros(n)
        self._beats = np.zeros(0) if beats is None else np.asarray(beats, dtype=np.float64)
        self._spot = np.zeros(n)
        self._duck = np.zeros(n)
        bar = task.duck
        self._bar = None
        if bar is not None:
            columns = [index(column) for column, _ in bar.points]
            reach = np.array([reach for _, reach in bar.points])
            self._bar = (columns, reach, bar.height, index(bar.along), bar.at)
        self._angles: list[FloatArray] | None = (
            [] if any(name in task.weights for name in DANCE_TERMS) else None
        )
        self._times: list[float] = []

    def __call__(self, t: float, sensors: FloatArray, targets: FloatArray) -> None:
        """Take one observation (the rollout's `Observer` signature)."""
        point = sensors[:, self._tracked]
        goal = np.where(self._moving, sensors[:, self._goal_column], self._goal_fixed)
        if self._wave is not None:
            self._distance = self._waving(t, point - goal)
        elif self._origin:
            self._distance = _angle(point, goal, sensors[:, self._origin])
        else:
            self._distance = np.linalg.norm(point - goal, axis=1)
        arrived = np.isfinite(self._arrival)
        self._path += np.where(arrived, np.linalg.norm(point - self._previous, axis=1), 0.0)
        inside = self._distance <= self.task.goal.radius
        self._arrival = np.where(~arrived & inside, t, self._arrival)
        self._settled = np.where(inside, np.minimum(self._settled, t), np.inf)
        self._previous = point
        if self._history is not None:
            self._history.append((t, self._distance))
            while self._history[0][0] < t - self.task.goal.hold - 1e-9:
                self._history.popleft()
        self._head_ticks += _touching(sensors, self._head)
        self._touch_ticks += _touching(sensors, self._touch)
        z, pitch = sensors[:, self._root[0]], sensors[:, self._root[1]]
        tilted = (np.abs(pitch) > self.task.max_tilt) | (z < self.task.min_height)
        if self._low is not None:
            tilted |= sensors[:, self._low[0]] < self._low[1]
        self._fallen_ticks += tilted | _touching(sensors, self._limbs)
        q, dq = sensors[:, self._q], sensors[:, self._dq]
        self._energy += self._power * (t - self._last_t)  # power held since the last tick
        figure = self.task.figure
        torque = np.clip(figure.kp * (targets - q) - figure.kv * dq, -self._torque, self._torque)
        self._power = np.abs(torque * dq).sum(axis=1)
        if self._posed:
            neutral = figure.neutral[self._posed]
            self._neutral = np.abs(q[:, self._posed] - neutral).mean(axis=1)
        self._spot += self._distance
        if self._bar is not None:
            points, reach, height, along, at = self._bar
            before = np.sign(at) * (at - sensors[:, along]) > 0.0
            above = np.maximum(0.0, (sensors[:, points] + reach).max(axis=1) - height)
            self._duck += np.where(before, above, 0.0)
        if self._angles is not None:
            self._angles.append(q[:, self._driven].copy())
            self._times.append(t)
        self._count += 1
        self._last_t = t

    def _waving(self, t: float, offset: FloatArray) -> FloatArray:
        """Take a wave's tick (``offset``: tracked − target, (P, 2)); its shortfall so far."""
        wave = self._wave
        assert wave is not None
        if t >= self.task.seconds - wave.window - 1e-9:
            phase = 2.0 * np.pi * wave.rate * t
            swing = offset[:, 0]
            self._wave_sums[:, 0] += swing * np.sin(phase)
            self._wave_sums[:, 1] += swing * np.cos(phase)
            self._wave_sums[:, 2] += np.maximum(0.0, -offset[:, 1])
            self._wave_sums[:, 3] += swing
            self._wave_basis += (np.sin(phase), np.cos(phase))
            self._wave_count += 1
        n = self._wave_count
        if n == 0:
            return np.full(len(offset), wave.amplitude)
        # the swing about its mean: a hand held still off to the side is no wave (over a
        # window of a fractional number of periods its offset would leak into the sum)
        mean = self._wave_sums[:, 3] / n
        sine = self._wave_sums[:, 0] - mean * self._wave_basis[0]
        cosine = self._wave_sums[:, 1] - mean * self._wave_basis[1]
        amplitude = 2.0 * np.hypot(sine, cosine) / n
        below = self._wave_sums[:, 2] / n
        shortfall = np.maximum(0.0, wave.amplitude - amplitude) + below
        if wave.centre_at_most is not None:
            shortfall += np.maximum(0.0, mean - wave.centre_at_most)
        return shortfall

    @property
    def observations(self) -> int:
        """How many observations were taken."""
        return self._count

    def terms(self) -> FloatArray:
        """(P, K) the term values (higher is better), columns in ``task.weights`` order."""
        if self._count == 0:
            raise FigureError("the meter has observed nothing: pass it as the rollout's observer")
        n = self._count
        duration = self._last_t if self._last_t > 0 else 1.0
        early = np.where(np.isfinite(self._settled), 1.0 - self._settled / duration, 0.0)
        values = {
            "distance": -self._held() if self._history is not None else -self._distance,
            "early": early,
            "still": -self._path,
            "head": -self._head_ticks / n,
            "fallen": -self._fallen_ticks / n,
            "neutral": -self._neutral,
            "energy": -self._energy,
            "touch": -self._touch_ticks / n,
            "spot": -self._spot / n,
            "duck": -self._duck / n,
        }
        if self._angles is not None:
            values |= self._dance_terms()
        return np.column_stack([values[name] for name in self.task.weights])

    def _held(self) -> FloatArray:
        """(P,) the farthest from the goal over the last ``goal.hold`` seconds observed."""
        assert self._history
        return np.max([d for _, d in self._history], axis=0)

    def _dance_terms(self) -> dict[str, FloatArray]:
        """``lift``, ``joints`` and ``smooth`` from the recorded (T, P, J) driven angles."""
        assert self._angles is not None
        angles = np.stack(self._angles)
        fps = (len(self._times) - 1) / self._times[-1] if self._times[-1] > 0 else 1.0
        per = [angles[:, p, :, None] for p in range(angles.shape[1])]
        swing = angles.std(axis=0) if len(angles) else np.zeros(angles.shape[1:])
        return {
            "lift": np.array([joint_lift(a, fps, self._beats) for a in per]),
            "joints": -np.maximum(0.0, 1.0 - swing / JOINT_SWING).mean(axis=1),
            "smooth": np.array([smoothness(a, fps) - 1.0 for a in per]),
        }


def _force_columns(figure: Figure, bodies: tuple[str, ...]) -> list[int]:
    axes = figure.force_axes
    return [figure.sensor_index(f"f{axis}_{body}") for body in bodies for axis in axes]


def _angle(point: FloatArray, goal: FloatArray, origin: FloatArray) -> FloatArray:
    """(P,) angle at ``origin`` between ``point`` and ``goal``, rad (π/2 where undefined)."""
    a, b = point - origin, goal - origin
    norms = np.linalg.norm(a, axis=1) * np.linalg.norm(b, axis=1)
    cosine = np.einsum("pk,pk->p", a, b) / np.where(norms > 0.0, norms, 1.0)
    return np.where(norms > 0.0, np.arccos(np.clip(cosine, -1.0, 1.0)), np.pi / 2)


def _touching(sensors: FloatArray, columns: list[int]) -> npt.NDArray[np.bool_]:
    if not columns:
        return np.zeros(len(sensors), dtype=bool)
    return (sensors[:, columns] != 0.0).any(axis=1)


def joint_lift(angles: npt.NDArray[np.floating], fps: float, beats: npt.ArrayLike) -> float:
    """The beat lift of joint motion: ``beat_lift`` with (T, J, 1) angles as the moving points.

    Args:
        angles: (T, J, 1) joint angles, rad, at ``fps``.
        fps: samples per second.
        beats: (K,) beat times, s.
    """
    if len(angles) < 3:
        return 0.0
    return beat_lift(angles, fps, beats)
