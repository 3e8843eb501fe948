"""Motion tasks as data: a figure in a scene, a goal, the terminals a controller sees, style.

Gritz & Hahn rate a motion by a main goal ("the distance between the figure
and the X at the end of the time allotment") plus style points. A `Task` holds
all of that for one task; `TaskMeter` (in `sinews.figures.terms`) measures
every term for a whole population from the rollout's per-tick sensors. The
engine has no special cases: a limbo pole is an extra body in the MJCF with a
contact sensor, a hand is a site with a position sensor, a goal is a tracked
point and a target, and goal-relative terminals such as ``gx = X − root_x``
are an affine map of the sensor columns (`Task.input_map`).

The terms (`sinews.figures.terms.TERMS`) are higher-is-better, as
`sinews.evolve.fitness` expects; a task weighs them.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import numpy.typing as npt

from sinews.figures._mujoco import require_mujoco
from sinews.figures.figure import Figure, FigureError
from sinews.figures.humanoid import humanoid
from sinews.figures.luxo import luxo
from sinews.figures.mjcf import fmt
from sinews.figures.terms import TERMS, TaskMeter

__all__ = [
    "LIMBO_BOARD_TOP",
    "LIMBO_SHARE",
    "TASKS",
    "TERMS",
    "Goal",
    "Task",
    "TaskMeter",
    "Wave",
    "all_tasks",
    "humanoid_reach",
    "luxo_hop",
    "luxo_limbo",
    "make_task",
    "standing_height",
]

FloatArray = npt.NDArray[np.float64]


@dataclass(frozen=True)
class Wave:
    """A wave of the tracked point: the ``distance`` of a `Goal` with a wave is how far the
    motion falls short of it, m (see `sinews.figures.terms`).

    Over the last ``window`` seconds, the first axis of tracked − target (e.g. the hand's
    sideways offset from the shoulder) must swing at ``rate`` Hz with at least
    ``amplitude`` m (the amplitude of its Fourier component at that rate), and the second
    (e.g. the hand's height over the shoulder) must stay above 0.

    Attributes:
        rate: Hz.
        amplitude: m.
        window: s, at the end of the trial.
    """

    rate: float = 1.5
    amplitude: float = 0.1
    window: float = 1.5

    def __post_init__(self) -> None:
        if not (self.rate > 0 and self.amplitude > 0 and self.window > 0):
            raise FigureError("a wave needs a positive rate, amplitude and window")


@dataclass(frozen=True)
class Goal:
    """Where a point of the figure must get to.

    Three kinds: a **position** (the tracked point on the target); a **direction**
    (with ``origin``: the angle at the origin between the tracked point and the
    target, rad — pointing); a **wave** (with ``wave``, see `Wave`).

    Attributes:
        tracked: sensor columns of the point, one per axis (e.g. ``("root_x",)``).
        target: per axis a fixed coordinate, m, or a sensor column (a moving target).
        names: the goal-relative terminal of each axis, target − tracked; or none
            (e.g. when the task offers the goal in the heading frame among its sensors).
        radius: the point has arrived within this distance, m (rad for a direction).
        origin: sensor columns of the origin of a direction goal, one per axis, or none.
        wave: a wave goal's rate, amplitude and window, or None.
    """

    tracked: tuple[str, ...]
    target: tuple[float | str, ...]
    names: tuple[str, ...]
    radius: float = 0.05
    origin: tuple[str, ...] = ()
    wave: Wave | None = None

    def __post_init__(self) -> None:
        if not (len(self.tracked) == len(self.target) >= 1):
            raise FigureError("a goal needs one tracked column, target and name per axis")
        if len(self.names) not in (0, len(self.tracked)):
            raise FigureError("a goal needs one tracked column, target and name per axis")
        if len(self.origin) not in (0, len(self.tracked)):
            raise FigureError("a direction goal needs one origin column per axis")
        if self.wave is not None and (self.origin or len(self.tracked) != 2):
            raise FigureError("a wave goal tracks two axes (swing, height) and has no origin")
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
        for column in (*self.sensors, *self.goal.tracked, *self.goal.target, *self.goal.origin):
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
        if not self.goal.names:
            return weights, offset
        for axis, (tracked, target) in enumerate(
            zip(self.goal.tracked, self.goal.target, strict=True)
        ):
            weights[index(tracked), first + axis] -= 1.0
            if isinstance(target, str):
                weights[index(target), first + axis] += 1.0
            else:
                offset[first + axis] = float(target)
        return weights, offset


def standing_height(figure: Figure) -> float:
    """How tall the figure stands at rest: the top of its highest geom, m above the floor."""
    mujoco = require_mujoco()
    model = figure.model()
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    tops = []
    for g in range(model.ngeom):
        if model.geom_bodyid[g] == 0:
            continue
        up = data.geom_xmat[g].reshape(3, 3)[2]  # the world z of each local axis
        size, kind = model.geom_size[g], model.geom_type[g]
        if kind == mujoco.mjtGeom.mjGEOM_SPHERE:
            reach = size[0]
        elif kind == mujoco.mjtGeom.mjGEOM_CAPSULE:
            reach = abs(up[2]) * size[1] + size[0]
        else:  # the geom's bounding box
            reach = float(np.abs(up) @ model.geom_aabb[g, 3:]) + float(up @ model.geom_aabb[g, :3])
        tops.append(data.geom_xpos[g, 2] + reach)
    return float(max(tops))


# -- the built-in tasks --------------------------------------------------------

STYLE = {"early": 0.2, "still": 0.5, "head": 3.0, "fallen": 2.0, "neutral": 0.1, "energy": 0.0}
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


LIMBO_SHARE = 0.8
"""The limbo pole's default height: this share of the lamp's standing height."""
LIMBO_BOARD_TOP = 1.0
"""Top of the board above the limbo bar, m: the lamp must pass under, not hop over."""


def luxo_limbo(
    pole_height: float | None = None,
    *,
    target: float = 1.0,
    pole_x: float | None = None,
    pole_radius: float = 0.02,
    seconds: float = 5.0,
) -> Task:
    """Limbo: hop to ``target`` passing under a pole whose underside is ``pole_height`` m up.

    The pole lies across the lamp's path at ``pole_x`` (default: halfway); it
    is solid, and any contact with it costs the ``touch`` term ("a large
    penalty for hitting his head on the limbo pole"). By default its underside
    is at `LIMBO_SHARE` of the lamp's `standing_height` (0.33 m of 0.41 m). A
    thin board closes the gap above the bar up to `LIMBO_BOARD_TOP` (in 2D the
    lamp could otherwise hop over the bar).
    """
    lamp = luxo()
    if pole_height is None:
        pole_height = round(LIMBO_SHARE * standing_height(lamp), 4)
    where = target / 2 if pole_x is None else pole_x
    if not 0.0 < pole_height < 1.0 or not 0.0 < where / target < 1.0:
        raise FigureError("luxo-limbo: the pole must be 0-1 m high and between the lamp and the X")
    root = ET.fromstring(lamp.xml)
    world = root.find("worldbody")
    assert world is not None
    height = pole_height + pole_radius
    pole = ET.SubElement(world, "body", {"name": "pole", "pos": fmt(where, 0, height)})
    shape = {"type": "capsule", "size": fmt(pole_radius), "fromto": fmt(0, -0.3, 0, 0, 0.3, 0)}
    collide = {"contype": "0", "conaffinity": "1", "rgba": "0.8 0.3 0.2 1"}  # with the lamp only
    ET.SubElement(pole, "geom", {"name": "pole", **shape, **collide})
    board = (LIMBO_BOARD_TOP - height - pole_radius) / 2  # half height of the board above
    ET.SubElement(pole, "geom", {"name": "board", "type": "box", **collide,
                                 "size": fmt(pole_radius / 2, 0.3, board),
                                 "pos": fmt(0, 0, pole_radius + board)})  # fmt: skip
    figure = Figure.from_mjcf(
        ET.tostring(root, encoding="unicode"),
        name="luxo",
        base_bodies=lamp.base_bodies,
        head_bodies=lamp.head_bodies,
        touch_bodies=("pole",),
        limb_bodies=lamp.limb_bodies,
    )
    return Task(
        name="luxo-limbo",
        figure=figure,
        goal=Goal(tracked=("root_x",), target=(float(target),), names=("gx",)),
        joints=("base_hinge", "elbow", "neck"),
        sensors=LUXO_SENSORS,
        weights={"distance": 1.0, **STYLE, "touch": 5.0},
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
        limb_bodies=person.limb_bodies,
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


def all_tasks() -> dict[str, Callable[..., Task]]:
    """The planar tasks (`TASKS`) and the 3D ones (`sinews.figures.tasks3d.TASKS_3D`)."""
    from sinews.figures.tasks3d import TASKS_3D  # it builds on this module

    return {**TASKS, **TASKS_3D}


def make_task(name: str, **options: Any) -> Task:
    """A built-in task by name, e.g. ``make_task("luxo-hop", target=1.5)``.

    Raises:
        FigureError: unknown task or options.
    """
    tasks = all_tasks()
    if name not in tasks:
        raise FigureError(f"no task called {name!r}; choose from {', '.join(tasks)}")
    try:
        return tasks[name](**options)
    except TypeError as exc:
        raise FigureError(f"{name}: {exc}") from None
