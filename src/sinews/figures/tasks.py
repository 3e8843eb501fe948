"""Motion tasks as data: a figure in a scene, a goal, the terminals a controller sees, style.

Gritz & Hahn rate a motion by a main goal ("the distance between the figure
and the X at the end of the time allotment") plus style points. A `Task` holds
all of that for one task, and `TaskMeter` measures every term for a whole
population from the rollout's per-tick sensors (pass it as the rollout's
``observer``). The engine has no special cases: a limbo pole is an extra body
in the MJCF with a contact sensor, a hand is a site with a position sensor,
a goal is a tracked point and a target, and goal-relative terminals such as
``gx = X − root_x`` are an affine map of the sensor columns (`Task.input_map`).

Terms (`TERMS`), each **higher is better** (penalties are ≤ 0), as
`sinews.evolve.fitness` expects:

- ``distance`` (the main goal): minus the tracked point's distance to the
  target at the end, m.
- ``early``: 1 − (time of first arrival within ``goal.radius``) / duration;
  0 if it never arrives. "Bonus for completing the motion early."
- ``still``: minus the path length of the tracked point after it first
  arrived, m. "Penalty for excess movement after the goal was met."
- ``head``: minus the fraction of ticks with any contact on a head body.
- ``fallen``: minus the fraction of ticks the root is tilted beyond
  ``max_tilt`` or lower than ``min_height`` ("falling over").
- ``neutral``: minus the mean |angle − neutral| of the driven joints at the
  end, rad. "Bonus for ending with joints at neutral angles."
- ``energy``: minus the work of the servos, Σ |τ · q̇| Δt over the ticks, J
  (τ from the PD law and each servo's torque limit); off in the built-ins.
- ``touch``: minus the fraction of ticks with contact on a touch body (the
  limbo pole).
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import numpy.typing as npt

from sinews.figures.figure import Figure, FigureError
from sinews.figures.humanoid import humanoid
from sinews.figures.luxo import luxo
from sinews.figures.mjcf import fmt

__all__ = [
    "TASKS",
    "TERMS",
    "Goal",
    "Task",
    "TaskMeter",
    "humanoid_reach",
    "luxo_hop",
    "luxo_limbo",
    "make_task",
]

FloatArray = npt.NDArray[np.float64]

TERMS = ("distance", "early", "still", "head", "fallen", "neutral", "energy", "touch")
"""Every fitness term a task can weigh; ``distance`` is always the main goal."""


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


class TaskMeter:
    """Measures a task's terms for P individuals from a rollout's observations.

    Pass it as ``rollout(..., observer=meter)``; then `terms` gives the
    (P, K) term values in the order of ``task.weights``.

    Args:
        task: the task.
        n_individuals: P.
    """

    def __init__(self, task: Task, n_individuals: int) -> None:
        figure = task.figure
        index = figure.sensor_index
        self.task = task
        self._tracked = [index(c) for c in task.goal.tracked]
        target = task.goal.target
        self._moving = np.array([isinstance(t, str) for t in target])
        self._goal_column = [index(t) if isinstance(t, str) else 0 for t in target]
        self._goal_fixed = np.array([0.0 if isinstance(t, str) else float(t) for t in target])
        self._head = _force_columns(figure, figure.head_bodies)
        self._touch = _force_columns(figure, figure.touch_bodies)
        self._root = index("root_z"), index("root_pitch")
        self._q = [index(f"q_{j}") for j in figure.joints]
        self._dq = [index(f"dq_{j}") for j in figure.joints]
        self._driven = task.actuators
        self._torque = np.abs(figure.model().actuator_forcerange).max(axis=1)
        n = n_individuals
        self._count = 0
        self._last_t = 0.0
        self._arrival = np.full(n, np.inf)
        self._path = np.zeros(n)
        self._previous = np.zeros((n, len(self._tracked)))
        self._distance = np.zeros(n)
        self._head_ticks = np.zeros(n)
        self._fallen_ticks = np.zeros(n)
        self._touch_ticks = np.zeros(n)
        self._energy = np.zeros(n)
        self._power = np.zeros(n)
        self._neutral = np.zeros(n)

    def __call__(self, t: float, sensors: FloatArray, targets: FloatArray) -> None:
        """Take one observation (the rollout's `Observer` signature)."""
        point = sensors[:, self._tracked]
        goal = np.where(self._moving, sensors[:, self._goal_column], self._goal_fixed)
        self._distance = np.linalg.norm(point - goal, axis=1)
        arrived = np.isfinite(self._arrival)
        self._path += np.where(arrived, np.linalg.norm(point - self._previous, axis=1), 0.0)
        self._arrival = np.where(
            ~arrived & (self._distance <= self.task.goal.radius), t, self._arrival
        )
        self._previous = point
        self._head_ticks += _touching(sensors, self._head)
        self._touch_ticks += _touching(sensors, self._touch)
        z, pitch = sensors[:, self._root[0]], sensors[:, self._root[1]]
        self._fallen_ticks += (np.abs(pitch) > self.task.max_tilt) | (z < self.task.min_height)
        q, dq = sensors[:, self._q], sensors[:, self._dq]
        self._energy += self._power * (t - self._last_t)  # power held since the last tick
        figure = self.task.figure
        torque = np.clip(figure.kp * (targets - q) - figure.kv * dq, -self._torque, self._torque)
        self._power = np.abs(torque * dq).sum(axis=1)
        neutral = self.task.figure.neutral[self._driven]
        self._neutral = np.abs(q[:, self._driven] - neutral).mean(axis=1)
        self._count += 1
        self._last_t = t

    @property
    def observations(self) -> int:
        """How many observations were taken."""
        return self._count

    def terms(self) -> FloatArray:
        """(P, K) the term values (higher is better), columns in ``task.weights`` order."""
        if self._count == 0:
            raise FigureError("the meter has observed nothing: pass it as the rollout's observer")
        n = self._count
        duration = self._last_t if self._last_t > 0 else 1.0
        early = np.where(np.isfinite(self._arrival), 1.0 - self._arrival / duration, 0.0)
        values = {
            "distance": -self._distance,
            "early": early,
            "still": -self._path,
            "head": -self._head_ticks / n,
            "fallen": -self._fallen_ticks / n,
            "neutral": -self._neutral,
            "energy": -self._energy,
            "touch": -self._touch_ticks / n,
        }
        return np.column_stack([values[name] for name in self.task.weights])


def _force_columns(figure: Figure, bodies: tuple[str, ...]) -> list[int]:
    return [figure.sensor_index(f"f{axis}_{body}") for body in bodies for axis in "xz"]


def _touching(sensors: FloatArray, columns: list[int]) -> npt.NDArray[np.bool_]:
    if not columns:
        return np.zeros(len(sensors), dtype=bool)
    return (sensors[:, columns] != 0.0).any(axis=1)


# -- the built-in tasks --------------------------------------------------------

STYLE = {"early": 0.2, "still": 0.5, "head": 1.0, "fallen": 1.0, "neutral": 0.1, "energy": 0.0}
"""Full style weights of the built-in tasks (the main goal ``distance`` weighs 1)."""

LUXO_SENSORS = (
    "time",
    "q_base_hinge",
    "q_elbow",
    "q_neck",
    "root_z",
    "root_vx",
    "root_vz",
    "fz_base",
)
"""The paper's lamp terminals: angles, height, velocity, base force, time (and ``gx``)."""


def luxo_hop(target: float = 1.0, *, seconds: float = 5.0) -> Task:
    """Hop to the X: the lamp's base must end at ``target`` m along x (0.5–2 m ahead or behind)."""
    if not 0.5 <= abs(target) <= 2.0:
        raise FigureError(f"luxo-hop: the target must be 0.5 to 2 m ahead or behind, got {target}")
    return Task(
        name="luxo-hop",
        figure=luxo(),
        goal=Goal(tracked=("root_x",), target=(float(target),), names=("gx",)),
        joints=("base_hinge", "elbow", "neck"),
        sensors=LUXO_SENSORS,
        weights={"distance": 1.0, **STYLE},
        seconds=seconds,
        params={"target": float(target)},
    )


def luxo_limbo(
    pole_height: float = 0.3,
    *,
    target: float = 1.0,
    pole_x: float | None = None,
    pole_radius: float = 0.02,
    seconds: float = 5.0,
) -> Task:
    """Limbo: hop to ``target`` passing under a pole whose underside is ``pole_height`` m up.

    The pole lies across the lamp's path at ``pole_x`` (default: halfway); it
    is solid, and any contact with it costs the ``touch`` term ("a large
    penalty for hitting his head on the limbo pole").
    """
    where = target / 2 if pole_x is None else pole_x
    if not 0.0 < pole_height < 1.0 or not 0.0 < where / target < 1.0:
        raise FigureError("luxo-limbo: the pole must be 0-1 m high and between the lamp and the X")
    lamp = luxo()
    root = ET.fromstring(lamp.xml)
    world = root.find("worldbody")
    assert world is not None
    height = pole_height + pole_radius
    pole = ET.SubElement(world, "body", {"name": "pole", "pos": fmt(where, 0, height)})
    shape = {"type": "capsule", "size": fmt(pole_radius), "fromto": fmt(0, -0.3, 0, 0, 0.3, 0)}
    collide = {"contype": "0", "conaffinity": "1", "rgba": "0.8 0.3 0.2 1"}  # with the lamp only
    ET.SubElement(pole, "geom", {"name": "pole", **shape, **collide})
    figure = Figure.from_mjcf(
        ET.tostring(root, encoding="unicode"),
        name="luxo",
        base_bodies=lamp.base_bodies,
        head_bodies=lamp.head_bodies,
        touch_bodies=("pole",),
    )
    return Task(
        name="luxo-limbo",
        figure=figure,
        goal=Goal(tracked=("root_x",), target=(float(target),), names=("gx",)),
        joints=("base_hinge", "elbow", "neck"),
        sensors=LUXO_SENSORS,
        weights={"distance": 1.0, **STYLE, "touch": 3.0},
        seconds=seconds,
        params={"pole_height": pole_height, "target": float(target), "pole_x": where},
    )


def humanoid_reach(
    target: tuple[float, float] | str = (0.45, 1.3), *, seconds: float = 3.0
) -> Task:
    """Touch a point (x, z) in front of the figure with the right hand, or ``"nose"``: its nose.

    The controller drives the waist, neck, right shoulder and right elbow; the
    other joints hold the standing pose. It sees those angles, both feet's
    floor forces, its hand's position, time, and the hand-to-target vector
    (``gx``, ``gz``).
    """
    person = humanoid()
    root = ET.fromstring(person.xml)
    for body, site, pos in (
        ("forearm_r", "hand_r", (0, 0, -0.305)),
        ("head", "nose", (0.1, 0, 0.1)),
    ):
        element = root.find(f".//body[@name='{body}']")
        assert element is not None
        ET.SubElement(element, "site", {"name": site, "pos": fmt(*pos), "size": "0.02"})
    figure = Figure.from_mjcf(
        ET.tostring(root, encoding="unicode"),
        name="humanoid",
        base_bodies=person.base_bodies,
        head_bodies=person.head_bodies,
        sites=("hand_r", "nose"),
    )
    nose = target == "nose"
    if not nose and (isinstance(target, str) or len(target) != 2):
        raise FigureError(f"humanoid-reach: the target is 'nose' or x,z, got {target!r}")
    goal_at: tuple[float | str, ...] = ("x_nose", "z_nose") if nose else tuple(map(float, target))
    joints = ("waist", "neck", "shoulder_r", "elbow_r")
    return Task(
        name="humanoid-reach",
        figure=figure,
        goal=Goal(tracked=("x_hand_r", "z_hand_r"), target=goal_at, names=("gx", "gz")),
        joints=joints,
        sensors=(
            "time",
            *(f"q_{j}" for j in joints),
            "fz_foot_l",
            "fz_foot_r",
            "x_hand_r",
            "z_hand_r",
        ),
        weights={"distance": 1.0, **STYLE, "neutral": 0.0},
        seconds=seconds,
        max_tilt=0.5,
        min_height=-0.25,
        params={"target": "nose" if nose else list(goal_at)},
    )


TASKS: Mapping[str, Callable[..., Task]] = {
    "luxo-hop": luxo_hop,
    "luxo-limbo": luxo_limbo,
    "humanoid-reach": humanoid_reach,
}
"""The built-in tasks by name."""


def make_task(name: str, **options: Any) -> Task:
    """A built-in task by name, e.g. ``make_task("luxo-hop", target=1.5)``.

    Raises:
        FigureError: unknown task or options.
    """
    if name not in TASKS:
        raise FigureError(f"no task called {name!r}; choose from {', '.join(TASKS)}")
    try:
        return TASKS[name](**options)
    except TypeError as exc:
        raise FigureError(f"{name}: {exc}") from None
