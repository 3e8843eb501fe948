"""Batched closed-loop rollout: a whole population of one figure, one controller call a tick.

Each control tick the controller reads the (P, S) sensor array and answers
(P, n_act) desired angles, which become the position servos' targets for the
next ``physics_hz / control_hz`` physics steps, stepped for all individuals at
once on C threads by `mujoco.batch.Batch`. Every individual starts at the
figure's rest state. Results are bit-identical for identical inputs, whatever
the batch size or thread count, provided the controller's rows are independent
(see `sinews.control.protocol.Controller`).
"""

from __future__ import annotations

import os
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from sinews.figures._mujoco import require_mujoco
from sinews.figures._population import Population
from sinews.figures.figure import Figure
from sinews.figures.sensors import make_reader
from sinews.trajectory import Trajectory

if TYPE_CHECKING:
    import mujoco

    from sinews.control.protocol import Controller

__all__ = ["Observer", "RolloutResult", "rollout"]

FloatArray = npt.NDArray[np.float64]

Observer = Callable[[float, FloatArray, FloatArray], None]
"""``observer(t, sensors, targets)``: a look at every control tick, then at the end.

Called after the controller answered at each tick with the (P, S) sensors it
saw and its (P, n_act) targets, and once more after the last tick with the
final sensors and the last targets. The arrays are reused: copy what you keep.
"""


@dataclass(frozen=True, eq=False)
class RolloutResult:
    """What a rollout of P individuals produced.

    Attributes:
        figure: the figure that was simulated.
        initial_x: (P,) root x at the start, m.
        final_x: (P,) root x at the end (for a failed individual: at its last
            healthy state), m.
        failed: (P,) True where the simulation went unstable (see `_population`).
        fail_time: (P,) seconds of a failed individual's last healthy state, else NaN.
        record_hz: frames per second of the recording, or None without one.
        frame_time: (T,) seconds of each recorded frame (the physics step nearest
            to ``k / record_hz``), or None.
        qpos: (T, P, nq) generalised coordinates per frame, or None.
        body_pos: (T, P, B, 3) world positions of the figure's bodies (world body
            excluded, order of ``figure.body_names``), or None.
    """

    figure: Figure
    initial_x: FloatArray
    final_x: FloatArray
    failed: npt.NDArray[np.bool_]
    fail_time: FloatArray
    record_hz: float | None = None
    frame_time: FloatArray | None = None
    qpos: FloatArray | None = None
    body_pos: npt.NDArray[np.float32] | None = None

    @property
    def distance(self) -> FloatArray:
        """(P,) final minus initial root x, m."""
        return self.final_x - self.initial_x

    def trajectory(self, individual: int) -> Trajectory:
        """Individual ``individual``'s recorded motion as a `Trajectory`.

        Nodes are the figure's bodies at their (x, z) positions, edges the
        parent-child links; ``qpos`` and ``body_pos`` are filled.
        """
        if self.qpos is None or self.body_pos is None or self.record_hz is None:
            raise ValueError("this rollout was not recorded: pass record=True")
        body_pos = self.body_pos[:, individual]
        return Trajectory(
            positions=body_pos[:, :, [0, 2]],
            fps=self.record_hz,
            edges=self.figure.edges,
            node_names=self.figure.body_names,
            qpos=self.qpos[:, individual],
            body_pos=body_pos,
            failed=bool(self.failed[individual]),
        )

    def trajectories(self) -> list[Trajectory]:
        """Every individual's recorded motion, in population order."""
        return [self.trajectory(i) for i in range(len(self.failed))]


def rollout(
    figure: Figure,
    controller: Controller,
    n_individuals: int,
    seconds: float,
    *,
    control_hz: int = 100,
    physics_hz: int = 1000,
    record: bool = False,
    record_hz: float = 60.0,
    nthread: int | None = None,
    max_speed: float = 1000.0,
    observer: Observer | None = None,
) -> RolloutResult:
    """Simulate ``n_individuals`` copies of ``figure``, each driven by its row of ``controller``.

    Args:
        figure: the figure to simulate.
        controller: answers (P, n_act) targets from (P, S) sensors each tick.
        n_individuals: P.
        seconds: simulated duration (rounded to whole control ticks).
        control_hz: controller calls per second; must divide ``physics_hz``.
        physics_hz: physics steps per second.
        record: keep ``qpos`` and ``body_pos`` frames for trajectories.
        record_hz: frames per second of the recording.
        nthread: C threads for the batch (default: every CPU).
        max_speed: a generalised velocity above this (m/s or rad/s) fails the row.
        observer: optional per-tick look at the sensors and targets (see `Observer`),
            e.g. to accumulate fitness terms; it does not change the motion.

    Returns:
        The per-individual results.

    Raises:
        ValueError: bad rates or sizes, or the controller answered the wrong shape.
        SinewsError: mujoco is not installed.
    """
    if n_individuals < 1 or seconds < 0 or control_hz < 1 or physics_hz % control_hz:
        raise ValueError("need n_individuals >= 1, seconds >= 0 and control_hz dividing physics_hz")
    if record and record_hz <= 0:
        raise ValueError("record_hz must be positive")
    substeps = physics_hz // control_hz
    n_ticks = round(seconds * control_hz)
    model = figure.model(timestep=1.0 / physics_hz)
    threads = nthread or os.cpu_count() or 1
    sim = Population(model, n_individuals, threads, max_speed)
    if figure.sites:  # site positions are read at t = 0 too (contact forces are 0 until a step)
        sim.batch.forward(stage=require_mujoco().mjtStage.mjSTAGE_POS)
    reader = make_reader(
        model, figure.joints, figure.contact_bodies, figure.sites, figure.root, figure.heading_joint
    )
    sensors = np.empty((n_individuals, reader.n_columns))
    initial_x = sim.qpos[:, 0].copy()
    total = n_ticks * substeps
    frame_steps = _frame_steps(total, physics_hz, record_hz) if record else np.zeros(0, int)
    frames: list[FloatArray] = []
    pending = iter(frame_steps.tolist())
    next_frame = next(pending, -1)
    if next_frame == 0:
        frames.append(sim.qpos.copy())
        next_frame = next(pending, -1)
    controller.reset(n_individuals)
    step = 0
    for tick in range(n_ticks):
        reader.read(sensors, sim.time, sim.qpos, sim.qvel, sim.sensordata)
        targets = np.asarray(controller.control(tick / control_hz, sensors), dtype=np.float64)
        if targets.shape != (n_individuals, figure.n_actuators):
            raise ValueError(
                f"controller answered shape {targets.shape}, "
                f"expected {(n_individuals, figure.n_actuators)}"
            )
        if observer is not None:
            observer(tick / control_hz, sensors, targets)
        sim.set_targets(targets)
        end = step + substeps
        while next_frame != -1 and next_frame <= end:
            sim.step(next_frame - step)
            step = next_frame
            frames.append(sim.qpos.copy())
            next_frame = next(pending, -1)
        sim.step(end - step)
        step = end
    if observer is not None and n_ticks:
        reader.read(sensors, sim.time, sim.qpos, sim.qvel, sim.sensordata)
        observer(n_ticks / control_hz, sensors, targets)
    result = RolloutResult(
        figure=figure,
        initial_x=initial_x,
        final_x=sim.qpos[:, 0].copy(),
        failed=sim.failed.copy(),
        fail_time=sim.fail_time.copy(),
    )
    if not record:
        return result
    qpos = np.stack(frames)
    return replace(
        result,
        record_hz=float(record_hz),
        frame_time=frame_steps / physics_hz,
        qpos=qpos,
        body_pos=_body_positions(model, qpos, threads),
    )


def _frame_steps(total: int, physics_hz: int, record_hz: float) -> npt.NDArray[np.int64]:
    """Physics step of each frame: the nearest to ``k / record_hz``, up to ``total``."""
    n_frames = int(np.floor(total / physics_hz * record_hz + 1e-9)) + 1
    return np.round(np.arange(n_frames) * physics_hz / record_hz).astype(np.int64)


def _body_positions(
    model: mujoco.MjModel, qpos: FloatArray, nthread: int
) -> npt.NDArray[np.float32]:
    """(T, P, B, 3) world positions of every body but the world, from (T, P, nq) frames."""
    mujoco = require_mujoco()
    n_frames, n = qpos.shape[:2]
    kinematics = mujoco.batch.Batch(model, nsim=n, nthread=nthread)
    rows = kinematics.bind("qpos")
    xpos = kinematics.bind("xpos")
    out = np.empty((n_frames, n, model.nbody - 1, 3), dtype=np.float32)
    for k in range(n_frames):
        rows[:] = qpos[k]
        kinematics.forward(stage=mujoco.mjtStage.mjSTAGE_POS)
        out[k] = xpos[:, 1:]
    return out
