"""A population of one figure on a `mujoco.batch.Batch`, with per-row failure handling.

An individual fails when, after a physics chunk, its state holds NaN or inf,
any generalised velocity exceeds ``max_speed``, MuJoCo raised a warning for it
(bad qpos/qvel/qacc/ctrl — MuJoCo then silently resets the row — or a full
contact/constraint buffer), MuJoCo raised an error in it, or its controller
asked for a non-finite target. A failed row is put back to its last healthy
state and never stepped again, so it cannot poison anything, and the others
run on untouched: each row's physics is independent of the others.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from sinews.figures._mujoco import require_mujoco

if TYPE_CHECKING:
    import mujoco

__all__ = ["Population"]

FloatArray = npt.NDArray[np.float64]
BoolArray = npt.NDArray[np.bool_]


class Population:
    """P simulations of one model stepped together, failed ones frozen.

    Args:
        model: the compiled figure (its timestep is the physics step).
        n: number of individuals P.
        nthread: C threads stepping the batch.
        max_speed: largest plausible |qvel| entry (m/s or rad/s).

    Attributes:
        qpos, qvel, ctrl, time, sensordata: live (P, …) views of the batch.
        failed: (P,) True once an individual failed.
        fail_time: (P,) seconds of a failed individual's last healthy state, else NaN.
    """

    def __init__(self, model: mujoco.MjModel, n: int, nthread: int, max_speed: float) -> None:
        mujoco = require_mujoco()
        self._error = mujoco.batch.SimulationError
        self.batch = mujoco.batch.Batch(model, nsim=n, nthread=nthread)
        self.batch.reset()
        self.qpos: FloatArray = self.batch.bind("qpos")
        self.qvel: FloatArray = self.batch.bind("qvel")
        self.ctrl: FloatArray = self.batch.bind("ctrl")
        self.time: FloatArray = self.batch.bind("time")
        self.sensordata: FloatArray = self.batch.bind("sensordata")
        self._state: FloatArray = self.batch.state
        self._max_speed = max_speed
        self._warnings = self._warning_counts()
        self.failed: BoolArray = np.zeros(n, dtype=bool)
        self.fail_time: FloatArray = np.full(n, np.nan)
        self._alive_ids: npt.NDArray[np.int32] | None = None

    def set_targets(self, targets: FloatArray) -> None:
        """Write (P, n_act) servo targets; a row with a non-finite target fails."""
        bad = ~np.isfinite(targets).all(axis=1) & ~self.failed
        if bad.any():
            self._fail(bad)
        np.copyto(self.ctrl, targets, where=~self.failed[:, None])

    def step(self, nstep: int) -> None:
        """Advance every healthy individual by ``nstep`` physics steps, then check them."""
        if nstep <= 0 or self.failed.all():
            return
        saved = self._state.copy()
        errored = np.zeros_like(self.failed)
        try:
            self.batch.step(ids=self._alive_ids, nstep=nstep)
        except self._error as exc:  # the others ran; these kept their state
            errored[exc.ids] = True
        bad = (errored | self._unhealthy()) & ~self.failed
        if bad.any():
            self._state[bad] = saved[bad]
            self._fail(bad)

    def _unhealthy(self) -> BoolArray:
        finite = np.isfinite(self._state).all(axis=1)
        with np.errstate(invalid="ignore"):
            fast = np.abs(self.qvel).max(axis=1) > self._max_speed
        return ~finite | fast | (self._warning_counts() > self._warnings)

    def _warning_counts(self) -> npt.NDArray[np.int64]:
        return self.batch.warning[:, :, 1].sum(axis=1, dtype=np.int64)

    def _fail(self, rows: BoolArray) -> None:
        """Freeze ``rows`` (already at a healthy state) and refresh their derived fields."""
        ids = np.flatnonzero(rows).astype(np.int32)
        self.batch.forward(ids=ids)
        self.failed |= rows
        self.fail_time[rows] = self.time[rows]
        alive = np.flatnonzero(~self.failed).astype(np.int32)
        self._alive_ids = alive if len(alive) < len(self.failed) else None
