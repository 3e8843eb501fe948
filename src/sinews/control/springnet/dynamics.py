"""The spring net's motion, integrated with the paper's explicit scheme, for P nets at once.

Each mass i feels the pull of every spring attached to it plus an optional
external (sensor) force, and the paper's update is applied with time step ts::

    F_i = sum_j k_ij (x_j - x_i) + f_i
    a_i = F_i / m_i
    v_i <- v_i + a_i ts
    x_i <- x_i + v_i ts      (with the new v_i: semi-implicit Euler)

The springs have rest length zero: each pulls its two masses together with a
force proportional to their distance. That is what the paper implies ("as long
as the initial positions of the point masses are not all identical and the
spring constants are not all zero, the point masses should immediately begin
to move"): with rest lengths equal to the initial distances every spring would
start relaxed and the net would never move. Internal forces cancel, so the
net's centre of mass stays where it starts (for zero external force).

`integrate` is the numba kernel, parallel over nets; `integrate_serial` runs the
same per-net code on one thread, for small jobs, where waking the threads costs
more than the work (a 4-mass net takes a few nanoseconds a step). Both do the
same floating-point operations in the same order per net, so they agree bit
for bit and a net's motion does not depend on which one ran it.
`integrate_reference` is the same maths in plain numpy, kept for tests.
`sensor_forces` and `sensor_forces_serial` turn sensors into forces likewise.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt
from numba import njit, prange

__all__ = [
    "integrate",
    "integrate_reference",
    "integrate_serial",
    "sensor_forces",
    "sensor_forces_serial",
]

PARALLEL_WORK = 200_000
"""Spring terms (P·n²·steps) from which the parallel kernels pay off."""

FloatArray = npt.NDArray[np.float64]


@njit(cache=True)
def _advance_net(
    p: int,
    masses: FloatArray,
    springs: FloatArray,
    x: FloatArray,
    v: FloatArray,
    force: FloatArray,
    n_steps: int,
    ts: float,
) -> None:
    n = x.shape[1]
    for _ in range(n_steps):
        for i in range(n):
            f = force[p, i]
            xi = x[p, i]
            for j in range(n):
                f += springs[p, i, j] * (x[p, j] - xi)
            v[p, i] += f / masses[p, i] * ts
        for i in range(n):
            x[p, i] += v[p, i] * ts


@njit(parallel=True, cache=True)
def integrate(
    masses: FloatArray,
    springs: FloatArray,
    x: FloatArray,
    v: FloatArray,
    force: FloatArray,
    n_steps: int,
    ts: float,
) -> None:
    """Advance P nets by ``n_steps`` steps of ``ts`` seconds, in place, on all threads.

    Args:
        masses: (P, n) point masses.
        springs: (P, n, n) spring constants, symmetric, zero diagonal.
        x: (P, n) positions, updated.
        v: (P, n) velocities, updated.
        force: (P, n) external force on each mass, held for all steps.
        n_steps: number of steps.
        ts: time step, seconds.
    """
    for p in prange(x.shape[0]):
        _advance_net(p, masses, springs, x, v, force, n_steps, ts)


@njit(cache=True)
def integrate_serial(
    masses: FloatArray,
    springs: FloatArray,
    x: FloatArray,
    v: FloatArray,
    force: FloatArray,
    n_steps: int,
    ts: float,
) -> None:
    """`integrate` on the calling thread only."""
    for p in range(x.shape[0]):
        _advance_net(p, masses, springs, x, v, force, n_steps, ts)


def integrate_reference(
    masses: FloatArray,
    springs: FloatArray,
    x: FloatArray,
    v: FloatArray,
    force: FloatArray,
    n_steps: int,
    ts: float,
) -> None:
    """The same update as `integrate`, vectorised in numpy over nets, in place."""
    degree = springs.sum(axis=2)
    for _ in range(n_steps):
        pull = np.einsum("pij,pj->pi", springs, x) - degree * x + force
        v += pull / masses * ts
        x += v * ts


@njit(cache=True)
def _net_forces(p: int, weights: FloatArray, sensors: FloatArray, out: FloatArray) -> None:
    n, n_sensors = weights.shape[1:]
    for i in range(n):
        f = 0.0
        for s in range(n_sensors):
            f += weights[p, i, s] * sensors[p, s]
        out[p, i] = f


@njit(parallel=True, cache=True)
def sensor_forces(weights: FloatArray, sensors: FloatArray, out: FloatArray) -> None:
    """External force on each mass from the sensors: ``out[p, i] = Σ_s w[p, i, s] s[p, s]``.

    A plain loop rather than BLAS, so that a net's force does not depend on how
    many nets are in the batch.

    Args:
        weights: (P, n, S) sensor-to-force weights.
        sensors: (P, S) sensor values.
        out: (P, n) forces, written.
    """
    for p in prange(sensors.shape[0]):
        _net_forces(p, weights, sensors, out)


@njit(cache=True)
def sensor_forces_serial(weights: FloatArray, sensors: FloatArray, out: FloatArray) -> None:
    """`sensor_forces` on the calling thread only."""
    for p in range(sensors.shape[0]):
        _net_forces(p, weights, sensors, out)
