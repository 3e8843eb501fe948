"""The spring-net controller: chosen masses' positions become desired joint angles.

Following seed 001, "the positions of one or more masses along the line are
used as the outputs" and mapped to the figure's desired joint angles; here the
map is linear per actuator, ``angle_a = offset_a + gain_a · x[outputs_a]``
(the servos then clamp it to the joint's range). The net runs at its own time
step ``ts`` and is advanced to each control tick's time.

Without ``input_weights`` the net is the paper's: it ignores the figure (the
paper calls this "closed loop", swapping the usual terms). With them, each
tick's sensor values push the masses, ``f_i = Σ_s w_is · sensor_s``, the input
the paper proposes as future work ("applying forces to the point masses").
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

from sinews.control.springnet.dynamics import (
    PARALLEL_WORK,
    integrate,
    integrate_serial,
    sensor_forces,
    sensor_forces_serial,
)
from sinews.control.springnet.genome import SpringNetError, SpringNetGenome

__all__ = ["SpringNetController", "stable_time_step"]

FloatArray = npt.NDArray[np.float64]


def stable_time_step(genome: SpringNetGenome) -> float:
    """The largest ``ts`` for which every net's free motion stays bounded.

    The explicit scheme is stable while ``ts · ω_max < 2``; ``ω_max²`` is at most
    the largest row sum of ``M⁻¹K``, ``max_i 2 Σ_j k_ij / m_i``.
    """
    bound = float((2.0 * genome.springs.sum(axis=2) / genome.masses).max(initial=0.0))
    return math.inf if bound == 0.0 else 2.0 / math.sqrt(bound)


class SpringNetController:
    """A population of spring nets driving a figure's servos (the `Controller` protocol).

    Args:
        genome: P nets of n masses.
        outputs: (n_act,) index of the mass whose position drives each actuator.
        gain: (n_act,) or scalar, radians per unit of position.
        offset: (n_act,) or scalar, radians (e.g. the figure's neutral angles).
        ts: the net's time step, seconds; must be below `stable_time_step`.
        input_weights: None (the paper's free-running net), or (n, S) weights
            shared by all nets, or (P, n, S) one set per net, from the S sensor
            columns to the force on each mass.

    Raises:
        SpringNetError: an output index, gain, offset, ts or weight is unusable.
    """

    def __init__(
        self,
        genome: SpringNetGenome,
        *,
        outputs: npt.ArrayLike,
        gain: npt.ArrayLike = 1.0,
        offset: npt.ArrayLike = 0.0,
        ts: float = 0.005,
        input_weights: npt.ArrayLike | None = None,
    ) -> None:
        self.genome = genome
        self.outputs = np.asarray(outputs, dtype=np.intp)
        if (
            self.outputs.ndim != 1
            or not ((self.outputs >= 0) & (self.outputs < genome.n_masses)).all()
        ):
            raise SpringNetError(f"outputs must be mass indices in [0, {genome.n_masses})")
        n_act = len(self.outputs)
        self.gain = _per_actuator(gain, n_act, "gain")
        self.offset = _per_actuator(offset, n_act, "offset")
        if not (0.0 < ts < stable_time_step(genome)):
            raise SpringNetError(
                f"ts must be in (0, {stable_time_step(genome):.4g}) for these springs"
            )
        self.ts = ts
        self.input_weights = _weights(input_weights, genome)
        self.x = genome.positions.copy()
        self.v = np.zeros_like(self.x)
        self._force = np.zeros_like(self.x)
        self._steps = 0

    def reset(self, n_individuals: int) -> None:
        """Put every net back at its initial positions, at rest, at time 0."""
        if n_individuals != self.genome.n_individuals:
            raise SpringNetError(
                f"{self.genome.n_individuals} spring nets cannot drive {n_individuals} figures"
            )
        self.x = self.genome.positions.copy()
        self.v = np.zeros_like(self.x)
        self._steps = 0

    def control(self, t: float, sensors: FloatArray) -> FloatArray:
        """Advance the nets to time ``t`` and map the output masses to angles.

        Args:
            t: seconds since reset.
            sensors: (P, S) the figure's sensor columns (used with input weights).

        Returns:
            (P, n_act) desired joint angles, rad.
        """
        target = math.floor(t / self.ts + 1e-9)
        n_steps = target - self._steps
        if n_steps > 0:
            weights = self.input_weights
            if weights is not None:
                if sensors.shape[1] != weights.shape[2]:
                    raise SpringNetError(
                        f"input weights expect {weights.shape[2]} sensors, got {sensors.shape[1]}"
                    )
                forces = sensor_forces if weights.size >= PARALLEL_WORK else sensor_forces_serial
                forces(weights, np.ascontiguousarray(sensors), self._force)
            g = self.genome
            work = g.springs.size * n_steps
            advance = integrate if work >= PARALLEL_WORK else integrate_serial
            advance(g.masses, g.springs, self.x, self.v, self._force, n_steps, self.ts)
            self._steps = target
        return self.offset + self.gain * self.x[:, self.outputs]


def _per_actuator(value: npt.ArrayLike, n_act: int, name: str) -> FloatArray:
    array = np.asarray(value, dtype=np.float64)
    if array.ndim > 1 or array.size not in (1, n_act) or not np.isfinite(array).all():
        raise SpringNetError(f"{name} must be a finite scalar or {n_act} values")
    return np.broadcast_to(array, (n_act,)).copy()


def _weights(value: npt.ArrayLike | None, genome: SpringNetGenome) -> FloatArray | None:
    if value is None:
        return None
    w = np.asarray(value, dtype=np.float64)
    p, n = genome.n_individuals, genome.n_masses
    if w.ndim == 2:
        w = np.broadcast_to(w, (p, *w.shape))
    if w.ndim != 3 or w.shape[:2] != (p, n) or not np.isfinite(w).all():
        raise SpringNetError(f"input_weights must have shape (n={n}, S) or (P={p}, n={n}, S)")
    return np.ascontiguousarray(w)
