"""A motion task as data: a figure in a scene, a goal, the terminals a controller sees, style.

`Task` holds everything one task is rated by (Gritz & Hahn: a main goal plus
style points); the built-in tasks are made in `sinews.figures.tasks`, and
`sinews.figures.terms.TaskMeter` measures a task's terms during a rollout.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import numpy.typing as npt

from sinews.figures.figure import Figure, FigureError

__all__ = ["TERMS", "Goal", "Task"]

FloatArray = npt.NDArray[np.float64]

TERMS = ("distance", "early", "still", "head", "fallen", "neutral", "energy", "touch")
"""Every fitness term a task can weigh (see `sinews.figures.terms`); ``distance`` is
always the main goal."""


@dataclass(frozen=True)
class Goal:
    """Where a point of the figure must get to.

    Attributes:
        tracked: sensor columns of the point, one per axis (e.g. ``("root_x",)``).
        target: per axis a fixed coordinate, m, or a sensor column (a moving target).
        names: the goal-relative terminal of each axis, target − tracked.
        radius: the point has arrived within this distance, m.
    """

    tracked: tuple[str, ...]
    target: tuple[float | str, ...]
    names: tuple[str, ...]
    radius: float = 0.05

    def __post_init__(self) -> None:
        if not (len(self.tracked) == len(self.target) == len(self.names) >= 1):
            raise FigureError("a goal needs one tracked column, target and name per axis")
        if not self.radius > 0:
            raise FigureError(f"the goal radius must be positive, got {self.radius}")


@dataclass(frozen=True, eq=False)
class Task:
    """A motion task: the scene, the goal, the controller's view and the fitness terms.

    Attributes:
        name: e.g. ``"luxo-hop"``.
        figure: the figure with the task's scene additions.
        goal: where the tracked point must get to.
        joints: the joints a controller drives; the others hold their neutral angles.
        sensors: the sensor columns offered to the controller as terminals.
        weights: full weight of each term (``distance`` first); others are 0.
        seconds: duration of a trial.
        max_tilt: the figure has fallen while |root pitch| exceeds this, rad.
        min_height: ... or while the root is lower than this, m (``root_z`` is
            measured from the rest pose, so this is usually negative).
        params: what the task was built with (for configs and titles).
    """

    name: str
    figure: Figure
    goal: Goal
    joints: tuple[str, ...]
    sensors: tuple[str, ...]
    weights: Mapping[str, float]
    seconds: float = 5.0
    max_tilt: float = 1.0
    min_height: float = -math.inf
    params: Mapping[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        unknown = [t for t in self.weights if t not in TERMS]
        if unknown or next(iter(self.weights), None) != "distance":
            raise FigureError(f"{self.name}: weights must start with 'distance' and use {TERMS}")
        for column in (*self.sensors, *self.goal.tracked, *self.goal.target):
            if isinstance(column, str):
                self.figure.sensor_index(column)
        if not self.joints:
            raise FigureError(f"{self.name}: drive at least one joint")
        for joint in self.joints:
            if joint not in self.figure.joints:
                raise FigureError(f"{self.name}: the figure has no joint {joint!r}")

    @property
    def terminals(self) -> tuple[str, ...]:
        """Names of the controller's input columns: the sensors, then the goal-relative ones."""
        return (*self.sensors, *self.goal.names)

    @property
    def actuators(self) -> npt.NDArray[np.intp]:
        """(J,) actuator index of each driven joint."""
        return np.array([self.figure.joints.index(j) for j in self.joints], dtype=np.intp)

    def input_map(self) -> tuple[FloatArray, FloatArray]:
        """The affine map from sensor columns to `terminals`: ``sensors @ W + b``.

        Returns:
            W: (S, V) weights.
            b: (V,) offsets.
        """
        index = self.figure.sensor_index
        weights = np.zeros((self.figure.n_sensors, len(self.terminals)))
        offset = np.zeros(len(self.terminals))
        for v, column in enumerate(self.sensors):
            weights[index(column), v] = 1.0
        first = len(self.sensors)
        for axis, (tracked, target) in enumerate(
            zip(self.goal.tracked, self.goal.target, strict=True)
        ):
            weights[index(tracked), first + axis] -= 1.0
            if isinstance(target, str):
                weights[index(target), first + axis] += 1.0
            else:
                offset[first + axis] = float(target)
        return weights, offset
