"""What a figure controller is: a population of controllers stepped together.

A controller holds one controller per individual and answers, each control
tick, every individual's desired joint angles at once, so a batched rollout
makes one Python call per tick for the whole population. Row ``p`` of the
answer must depend only on row ``p`` of the sensors (and the controller's own
state for individual ``p``): an individual's motion must not depend on who else
is in the batch.
"""

from __future__ import annotations

from typing import Protocol

import numpy as np
import numpy.typing as npt

__all__ = ["Controller"]


class Controller(Protocol):
    """The interface `sinews.figures.rollout` drives."""

    def reset(self, n_individuals: int) -> None:
        """Return every individual's controller to its initial state.

        Args:
            n_individuals: P, the number of rows the rollout will pass.
        """
        ...

    def control(self, t: float, sensors: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
        """Desired joint angles for every individual at time ``t``.

        Args:
            t: seconds since the start; successive calls have increasing ``t``.
            sensors: (P, S) the figure's sensor columns.

        Returns:
            (P, n_act) desired angles, rad, in the figure's actuator order.
        """
        ...
