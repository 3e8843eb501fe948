"""The simplest controller: hold fixed targets (e.g. the neutral pose) forever."""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

__all__ = ["HoldPose"]


class HoldPose:
    """Every individual asks for the same or its own fixed joint angles at all times.

    Args:
        targets: (n_act,) angles for all individuals, or (P, n_act) one row each.
    """

    def __init__(self, targets: npt.ArrayLike) -> None:
        self.targets = np.asarray(targets, dtype=np.float64)
        self._out = np.empty((0, self.targets.shape[-1]))

    def reset(self, n_individuals: int) -> None:
        """Prepare the (P, n_act) answer for ``n_individuals`` rows."""
        self._out = np.ascontiguousarray(
            np.broadcast_to(self.targets, (n_individuals, self.targets.shape[-1]))
        )

    def control(self, t: float, sensors: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
        """The held targets, (P, n_act), whatever the time and sensors."""
        return self._out
