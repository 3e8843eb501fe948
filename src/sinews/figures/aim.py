"""A held joint turned by a fixed rule to face the goal (a 3D lamp's swivel).

Seed 003's humanoid had joints its programs did not drive, "under simple dynamic
control". `Aim` is such a rule for a hinge about the vertical whose angle turns
the figure's heading frame (`Figure.heading_joint`): each tick its target is its
angle plus the goal's bearing in that frame, so the part above it faces the goal
and the programs drive the motion along it. Near the goal the bearing is scaled
down (to 0 on it), so a figure that lands a little past the X does not spin round.
`AimedController` applies the rule on top of any controller.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from sinews.control.protocol import Controller
from sinews.figures.figure import Figure, FigureError

__all__ = ["Aim", "AimedController"]

FloatArray = npt.NDArray[np.float64]


@dataclass(frozen=True)
class Aim:
    """A held hinge aimed at the goal: target = angle + atan2(left, ahead) · min(1, d / near).

    Attributes:
        joint: the actuated hinge (no program drives it), e.g. ``"swivel"``.
        angle: the sensor column of its angle, rad.
        ahead: the goal's forward offset in the heading frame, a sensor column (m).
        left: its leftward offset, a sensor column (m).
        near: within this distance d of the goal, m, the bearing is scaled by d / near.
    """

    joint: str
    angle: str
    ahead: str
    left: str
    near: float = 0.2

    def __post_init__(self) -> None:
        if not self.near > 0:
            raise FigureError(f"an aim's near distance must be positive, got {self.near}")


class AimedController:
    """``inner`` with the aimed joint's target replaced by the rule (the `Controller` protocol).

    Args:
        inner: the controller of the other joints (its target for the aimed joint is ignored).
        figure: the figure it drives.
        aim: the rule.
    """

    def __init__(self, inner: Controller, figure: Figure, aim: Aim) -> None:
        if aim.joint not in figure.joints:
            raise FigureError(f"{figure.name} has no actuated joint {aim.joint!r} to aim")
        self.inner = inner
        self._actuator = figure.joints.index(aim.joint)
        self._columns = [figure.sensor_index(c) for c in (aim.angle, aim.ahead, aim.left)]
        self._near = aim.near

    def reset(self, n_individuals: int) -> None:
        """Reset the inner controller."""
        self.inner.reset(n_individuals)

    def control(self, t: float, sensors: FloatArray) -> FloatArray:
        """The inner controller's (P, n_act) targets, the aimed joint's from (P, S) sensors."""
        targets = np.array(self.inner.control(t, sensors), dtype=np.float64)
        angle, ahead, left = (sensors[:, c] for c in self._columns)
        fade = np.minimum(1.0, np.hypot(ahead, left) / self._near)
        targets[:, self._actuator] = angle + np.arctan2(left, ahead) * fade
        return targets
