"""A spring-net run's settings (seed 001): the figure, the trial, the net, the rates."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from sinews.control.springnet import SpringNetController
from sinews.errors import SinewsError
from sinews.evolve.alton import SpringNetEncoding
from sinews.experiments.figures import FIGURES, make_figure
from sinews.figures import Figure
from sinews.limits import MAX_MASSES, check_whole

__all__ = ["NET_TIME_STEP", "PHYSICS_HZ", "TERMS", "SpringNetSettings"]

FloatArray = npt.NDArray[np.float64]

NET_TIME_STEP = 0.005
"""The nets' own time step, seconds (stable for every net of up to ~60 masses)."""
PHYSICS_HZ = {"snake": 500, "luxo": 1000, "humanoid": 1000}
"""Default physics rate per figure: the snake's distances at 500 Hz match 1 kHz (r = 0.996
over 2000 random nets); the Luxo's hops are chaotic, so it keeps its model's 1 kHz."""
TERMS = {"distance": 1.0}
"""The fitness terms and their weights: the paper's distance only."""


@dataclass(frozen=True)
class SpringNetSettings:
    """How a run's nets are simulated.

    Attributes:
        figure: the figure's name (see `FIGURES`).
        seconds: trial length.
        masses: n, masses per net.
        physics_hz: physics steps per second.
        control_hz: controller ticks per second (divides ``physics_hz``).
    """

    figure: str
    seconds: float
    masses: int
    physics_hz: int
    control_hz: int = 100

    @classmethod
    def from_values(cls, values: Mapping[str, Any]) -> SpringNetSettings:
        """Settings from run-file/option/config values, defaults filled per figure.

        Raises:
            SinewsError: an unknown figure or a bad number, naming the setting.
        """
        figure = values.get("figure")
        if figure not in FIGURES:
            raise SinewsError(f"no figure called {figure!r}; choose from {', '.join(FIGURES)}")
        masses = values.get("masses") or max(4, make_figure(figure).n_actuators)
        settings = cls(
            figure=figure,
            seconds=_number(values.get("seconds"), "seconds"),
            masses=check_whole("masses", masses, 2, MAX_MASSES),
            physics_hz=_whole(values.get("physics_hz") or PHYSICS_HZ[figure], "physics_hz", 1),
            control_hz=_whole(values.get("control_hz"), "control_hz", 1),
        )
        if settings.physics_hz % settings.control_hz:
            raise SinewsError("control_hz must divide physics_hz")
        return settings

    def to_dict(self) -> dict[str, Any]:
        """The settings as stored in a run's config."""
        return {
            "figure": self.figure,
            "seconds": self.seconds,
            "masses": self.masses,
            "physics_hz": self.physics_hz,
            "control_hz": self.control_hz,
        }

    @property
    def encoding(self) -> SpringNetEncoding:
        """Where masses, springs and positions sit in a gene vector."""
        return SpringNetEncoding(self.masses)

    def controller(self, figure: Figure, genes: FloatArray) -> SpringNetController:
        """The controller of (P, G) genes driving ``figure``."""
        low, high = figure.joint_range[:, 0], figure.joint_range[:, 1]
        gain = np.where(np.isfinite(high - low), 0.5 * (high - low), 1.0)
        return SpringNetController(
            self.encoding.decode(genes),
            outputs=np.arange(figure.n_actuators) % self.masses,
            gain=gain,
            offset=figure.neutral,
            ts=NET_TIME_STEP,
        )


def _number(value: object, name: str) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float) or not value > 0:
        raise SinewsError(f"{name} must be a positive number, got {value!r}")
    return float(value)


def _whole(value: object, name: str, least: int) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or value < least:
        raise SinewsError(f"{name} must be a whole number >= {least}, got {value!r}")
    return value
