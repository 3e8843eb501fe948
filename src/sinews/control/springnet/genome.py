"""The spring-net genome of seed 001: masses, spring constants and initial positions.

A spring net (Alton, "Spring Net Controllers for Articulated Figures") is n
point masses on a line joined by springs. The paper describes a net by exactly
three things, and so does this genome, for a whole population at once:

1. the masses m_1..m_n,
2. the spring constants k_ij of the springs between masses i and j (0: no spring),
3. the initial positions x_1..x_n.

Valid ranges (checked by `SpringNetGenome.validate`, drawn by `random`):

- ``masses`` in [`MASS_RANGE`] (kg-like units),
- ``springs`` in [`SPRING_RANGE`], symmetric, zero on the diagonal, zero where a
  given topology has no spring,
- ``positions`` in [`POSITION_RANGE`] (the net's axis has no unit; a controller's
  gain turns positions into radians).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from sinews.errors import SinewsError

__all__ = [
    "MASS_RANGE",
    "POSITION_RANGE",
    "SPRING_RANGE",
    "SpringNetError",
    "SpringNetGenome",
]

FloatArray = npt.NDArray[np.float64]

MASS_RANGE = (0.1, 10.0)
SPRING_RANGE = (0.0, 100.0)
POSITION_RANGE = (-1.0, 1.0)


class SpringNetError(SinewsError):
    """A spring-net genome or controller setting out of range, naming the field."""


@dataclass(frozen=True, eq=False)
class SpringNetGenome:
    """P spring nets of n masses each, as float64 arrays.

    Attributes:
        masses: (P, n) point masses, in `MASS_RANGE`.
        springs: (P, n, n) spring constants k_ij, symmetric, zero diagonal, in
            `SPRING_RANGE`.
        positions: (P, n) initial positions x_i, in `POSITION_RANGE`.
    """

    masses: FloatArray
    springs: FloatArray
    positions: FloatArray

    def __post_init__(self) -> None:
        for name in ("masses", "springs", "positions"):
            object.__setattr__(
                self, name, np.ascontiguousarray(getattr(self, name), dtype=np.float64)
            )
        self.validate()

    @property
    def n_individuals(self) -> int:
        """P."""
        return int(self.masses.shape[0])

    @property
    def n_masses(self) -> int:
        """n."""
        return int(self.masses.shape[1])

    def validate(self) -> None:
        """Raise `SpringNetError` naming the first field that is out of shape or range."""
        if self.masses.ndim != 2:
            raise SpringNetError(f"masses must have shape (P, n), got {self.masses.shape}")
        p, n = self.masses.shape
        shapes = {"springs": (p, n, n), "positions": (p, n)}
        for name, shape in shapes.items():
            if getattr(self, name).shape != shape:
                raise SpringNetError(
                    f"{name} must have shape {shape}, got {getattr(self, name).shape}"
                )
        ranges = {"masses": MASS_RANGE, "springs": SPRING_RANGE, "positions": POSITION_RANGE}
        for name, (lo, hi) in ranges.items():
            value = getattr(self, name)
            if not (np.isfinite(value).all() and (value >= lo).all() and (value <= hi).all()):
                raise SpringNetError(f"{name} must lie in [{lo}, {hi}]")
        if not np.array_equal(self.springs, self.springs.transpose(0, 2, 1)):
            raise SpringNetError("springs must be symmetric (k_ij == k_ji)")
        if np.diagonal(self.springs, axis1=1, axis2=2).any():
            raise SpringNetError("springs must be zero on the diagonal (no self-springs)")

    def take(self, rows: npt.ArrayLike) -> SpringNetGenome:
        """The genomes of the given individuals, (len(rows),) in that order."""
        index = np.asarray(rows, dtype=np.intp)
        return SpringNetGenome(self.masses[index], self.springs[index], self.positions[index])

    @classmethod
    def random(
        cls,
        rng: np.random.Generator,
        n_individuals: int,
        n_masses: int,
        *,
        topology: npt.ArrayLike | None = None,
    ) -> SpringNetGenome:
        """Uniformly random nets within the valid ranges.

        Args:
            rng: the source of randomness.
            n_individuals: P.
            n_masses: n.
            topology: (n, n) bool, which pairs have a spring (symmetrised, diagonal
                ignored); default every pair.

        Returns:
            The genomes.
        """
        shape = (n_individuals, n_masses)
        masses = rng.uniform(*MASS_RANGE, size=shape)
        upper = np.triu(rng.uniform(*SPRING_RANGE, size=(*shape, n_masses)), k=1)
        springs = (upper + upper.transpose(0, 2, 1)) * spring_mask(n_masses, topology)
        positions = rng.uniform(*POSITION_RANGE, size=shape)
        return cls(masses, springs, positions)


def spring_mask(n_masses: int, topology: npt.ArrayLike | None) -> FloatArray:
    """(n, n) 1.0 where a spring may exist: symmetric, zero diagonal."""
    if topology is None:
        mask = np.ones((n_masses, n_masses), dtype=bool)
    else:
        mask = np.asarray(topology, dtype=bool)
        if mask.shape != (n_masses, n_masses):
            raise SpringNetError(f"topology must have shape {(n_masses, n_masses)}")
        mask = mask | mask.T
    np.fill_diagonal(mask, False)
    return mask.astype(np.float64)
