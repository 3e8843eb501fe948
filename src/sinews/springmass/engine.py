"""Run the frame loop on a batch: `simulate` and what it records."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np
import numpy.typing as npt

from sinews.springmass.batch import BodyBatch, EngineParams, SimState
from sinews.springmass.body import BodyError
from sinews.springmass.kernels import simulate_kernel, simulate_serial
from sinews.springmass.reference import simulate_reference
from sinews.trajectory import Trajectory

__all__ = ["SERIAL_BODIES", "Backend", "Recording", "simulate"]

Backend = Literal["numba", "numpy"]

SERIAL_BODIES = 32
"""Batches this small run on one thread (`simulate_serial`, bit for bit the same): the
studio's 12-25 dancers gain little from threads, and a first start then compiles only
the serial kernel (8 s against 20 s on an empty numba cache)."""


@dataclass(frozen=True, eq=False)
class Recording:
    """Frames recorded by `simulate`: frame 0 is the start, frame r is after r x stride steps.

    Attributes:
        positions: (R, P, N, 2) float32 metres.
        forces: (R, P, N, 2) float32 net force acting in the step after each frame, or None.
        fps: frames per second of the recording (1 / (dt x stride)).
    """

    positions: npt.NDArray[np.float32]
    forces: npt.NDArray[np.float32] | None
    fps: float

    def trajectory(self, batch: BodyBatch, state: SimState, index: int) -> Trajectory:
        """Body ``index`` of the batch as a `Trajectory` (padding removed)."""
        body = batch.bodies[index]
        n = body.n_nodes
        return Trajectory(
            positions=self.positions[:, index, :n],
            fps=self.fps,
            edges=body.edges,
            node_names=body.names,
            radii=body.radius.astype(np.float32),
            colors=body.colors,
            forces=None if self.forces is None else self.forces[:, index, :n],
            failed=bool(state.failed[index]),
        )


def simulate(
    batch: BodyBatch,
    state: SimState,
    n_steps: int,
    params: EngineParams | None = None,
    *,
    external: npt.ArrayLike | None = None,
    drive: npt.ArrayLike | None = None,
    phase: npt.ArrayLike | None = None,
    pose: npt.ArrayLike | None = None,
    record: bool = True,
    record_stride: int = 1,
    record_forces: bool = False,
    backend: Backend = "numba",
) -> tuple[SimState, Recording | None]:
    """Advance ``state`` by ``n_steps`` frames of the paper's loop.

    Args:
        batch: the bodies.
        state: where they are; not modified (a new state is returned).
        n_steps: steps to take, >= 0.
        params: engine settings (defaults: 60 Hz, gravity, floor).
        external: caller forces in newtons, (P, N, 2) for every step or
            (n_steps, P, N, 2) one row per step.
        drive: (D, C) values >= 0 that drive the actuators; row k is read at
            global step k (``state.step`` counts from 0), none after the last row.
        phase: (D,) phase signal in [0, 1) for SWAY and SHAKE actuators (default zeros).
        pose: (Q, K) pose signals that move the home targets by the bodies'
            ``pose_basis``; row k is read at global step k, none after the last row.
        record: keep the positions every ``record_stride`` steps.
        record_forces: also keep the net force on each node (debug overlay).
        backend: ``"numba"`` (fast) or ``"numpy"`` (the reference).

    Returns:
        The new state and the recording (None when ``record`` is False). A
        body that blows up is frozen and flagged in ``state.status``; the
        others are unaffected.
    """
    params = params or EngineParams()
    if n_steps < 0:
        raise BodyError("n_steps must be >= 0")
    if record_stride < 1:
        raise BodyError("record_stride must be >= 1")
    n_bodies, big_n = batch.rest.shape[:2]
    if state.positions.shape != (n_bodies, big_n, 2):
        raise BodyError("state does not belong to this batch")
    ext = _external(external, n_steps, (n_bodies, big_n, 2))
    drive_table, phase_row = _drive(batch, drive, phase)
    pose_table = _pose(batch, pose)
    new = state.copy()
    n_rec = n_steps // record_stride + 1 if record else 0
    rec_pos = np.zeros((n_rec, n_bodies, big_n, 2), dtype=np.float32)
    rec_force = np.zeros((n_rec if record_forces else 0, n_bodies, big_n, 2), dtype=np.float32)
    if backend == "numpy":
        run = simulate_reference
    else:
        run = simulate_serial if n_bodies <= SERIAL_BODIES else simulate_kernel
    run(
        new.positions, new.velocities, new.status, new.failed_step,
        batch.n_nodes, batch.n_edges, batch.n_attractions, batch.rest, batch.mass,
        batch.weight, batch.radius, batch.home, batch.wiggle,
        batch.edges, batch.rest_length, batch.strength, batch.easing,
        batch.attraction, batch.attraction_strength, batch.attraction_reach,
        batch.drag, batch.seeds, batch.n_actuators, batch.actuator_node, batch.actuator_kind,
        batch.actuator_channels, batch.actuator_strength, batch.actuator_custom,
        batch.pose_basis, drive_table, phase_row, pose_table, ext, state.step, n_steps,
        params.dt, params.gravity, params.floor, params.floor_y, params.friction,
        params.restitution, *params.home_follow, params.wiggle_steps,
        params.wiggle_seeded_phase, params.max_speed,
        record_stride, rec_pos, rec_force,
    )  # fmt: skip
    new.step = state.step + n_steps
    if not record:
        return new, None
    fps = 1.0 / (params.dt * record_stride)
    return new, Recording(rec_pos, rec_force if record_forces else None, fps)


def _drive(
    batch: BodyBatch, drive: npt.ArrayLike | None, phase: npt.ArrayLike | None
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    table = np.zeros((0, 1)) if drive is None else np.asarray(drive, dtype=np.float64)
    if table.ndim != 2:
        raise BodyError(f"drive must have shape (steps, channels), got {table.shape}")
    if not np.all(np.isfinite(table)) or (table.size and table.min() < 0):
        raise BodyError("drive values must be finite and >= 0")
    used = batch.n_actuators > 0
    if drive is not None and used.any():
        highest = max(int(b.actuator_channels[:, 1].max()) for b in batch.bodies if b.n_actuators)
        if highest >= table.shape[1]:
            raise BodyError(f"an actuator reads channel {highest}; drive has {table.shape[1]}")
    row = np.zeros(len(table)) if phase is None else np.asarray(phase, dtype=np.float64)
    if row.shape != (len(table),):
        raise BodyError(f"phase must have shape ({len(table)},), got {row.shape}")
    return np.ascontiguousarray(table), row


def _pose(batch: BodyBatch, pose: npt.ArrayLike | None) -> npt.NDArray[np.float64]:
    n_signals = batch.pose_basis.shape[2]
    if pose is None:
        return np.zeros((0, n_signals))
    table = np.asarray(pose, dtype=np.float64)
    if table.ndim != 2 or table.shape[1] != n_signals:
        raise BodyError(f"pose must have shape (steps, {n_signals}), got {table.shape}")
    if not np.all(np.isfinite(table)):
        raise BodyError("pose values must be finite")
    return np.ascontiguousarray(table)


def _external(
    external: npt.ArrayLike | None, n_steps: int, shape: tuple[int, int, int]
) -> npt.NDArray[np.float64]:
    if external is None:
        return np.zeros((0, *shape))
    ext = np.asarray(external, dtype=np.float64)
    if ext.shape == shape:
        return ext[None]
    if ext.shape == (n_steps, *shape):
        return np.ascontiguousarray(ext)
    raise BodyError(f"external forces must have shape {shape} or {(n_steps, *shape)}")
