"""A motion task as data: a figure in a scene, a goal, the terminals a controller sees, style.

`Task` holds everything one task is rated by (Gritz & Hahn: a main goal plus
style points); the built-in tasks are made in `sinews.figures.tasks`, and
`sinews.figures.terms.TaskMeter` measures a task's terms during a rollout.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import numpy.typing as npt

from sinews.control.music_input import MUSIC_TERMINALS
from sinews.figures._mujoco import require_mujoco
from sinews.figures.aim import Aim
from sinews.figures.figure import Figure, FigureError
from sinews.limits import MAX_SECONDS

__all__ = [
    "DANCE_STYLE",
    "MAIN_GOALS",
    "STYLE",
    "TERMS",
    "TOUCH_HOLD",
    "Duck",
    "Goal",
    "Task",
    "Wave",
    "dance_task",
    "standing_height",
]

FloatArray = npt.NDArray[np.float64]

TERMS = ("distance", "early", "still", "head", "fallen", "neutral", "energy", "touch",
         "lift", "spot", "joints", "smooth", "duck")  # fmt: skip
"""Every fitness term a task can weigh (see `sinews.figures.terms`); the main goal is
``distance``, or ``lift`` for a dance."""
MAIN_GOALS = ("distance", "lift")
"""The terms a task's weights may start with: its main goal."""


STYLE = {"early": 0.2, "still": 0.5, "head": 3.0, "fallen": 2.0, "neutral": 0.1, "energy": 0.0}
"""Full style weights of the built-in tasks (the main goal ``distance`` weighs 1)."""
TOUCH_HOLD = 0.5
"""A touch or a pointing arm is held: the humanoids' reach, touch, nose and point goals are
rated by the farthest the hand (or the arm's direction) gets from the target over the trial's
last this many seconds. Rated at the last tick alone, four of five planar reach bests swung
the hand through the point, or threw the trunk forward as the clock stopped."""
DANCE_STYLE = {"head": 3.0, "fallen": 2.0, "spot": 0.3, "joints": 0.3, "smooth": 0.3}
"""Full style weights of a dance (the main goal ``lift`` weighs 1): stay upright, near the
spot, use every driven joint, move smoothly."""


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


@dataclass(frozen=True)
class Wave:
    """A wave of the tracked point: the ``distance`` of a `Goal` with a wave is how far the
    motion falls short of it, m (see `sinews.figures.terms`).

    Over the last ``window`` seconds, the first axis of tracked − target (e.g. the hand's
    sideways offset from the shoulder) must swing at ``rate`` Hz with at least
    ``amplitude`` m (the amplitude of its Fourier component at that rate), about a centre
    (its mean) of at most ``centre_at_most`` m, and the second (e.g. the hand's height
    over the shoulder) must stay above 0.

    Attributes:
        rate: Hz.
        amplitude: m.
        window: s, at the end of the trial.
        centre_at_most: m, or None for anywhere (e.g. 0 for the right hand: not inward of
            the shoulder, so a hand fanning the face is no wave).
    """

    rate: float = 1.5
    amplitude: float = 0.1
    window: float = 1.5
    centre_at_most: float | None = None

    def __post_init__(self) -> None:
        if not (self.rate > 0 and self.amplitude > 0 and self.window > 0):
            raise FigureError("a wave needs a positive rate, amplitude and window")


@dataclass(frozen=True)
class Goal:
    """Where a point of the figure must get to.

    Three kinds: a **position** (the tracked point on the target); a **direction**
    (with ``origin``: the angle at the origin between the tracked point and the
    target, rad — pointing); a **wave** (with ``wave``, see `Wave`). A position or
    direction is measured at the end, or, with ``hold``, as the farthest it gets from
    the target over the last ``hold`` seconds (a touch must be held, not swung through).

    Attributes:
        tracked: sensor columns of the point, one per axis (e.g. ``("root_x",)``).
        target: per axis a fixed coordinate, m, or a sensor column (a moving target).
        names: the goal-relative terminals target − tracked of the first axes (all, some
            or none: e.g. none when the task offers the goal in the heading frame among its
            sensors; a lamp's X has one for x and none for the base's height).
        radius: the point has arrived within this distance, m (rad for a direction).
        origin: sensor columns of the origin of a direction goal, one per axis, or none.
        wave: a wave goal's rate, amplitude and window, or None.
        hold: s at the end over which the goal is measured (its worst), or 0: at the end.
    """

    tracked: tuple[str, ...]
    target: tuple[float | str, ...]
    names: tuple[str, ...]
    radius: float = 0.05
    origin: tuple[str, ...] = ()
    wave: Wave | None = None
    hold: float = 0.0

    def __post_init__(self) -> None:
        if not (len(self.tracked) == len(self.target) >= 1):
            raise FigureError("a goal needs one tracked column and target per axis")
        if len(self.names) > len(self.tracked):
            raise FigureError("a goal has at most one terminal name per axis")
        if len(self.origin) not in (0, len(self.tracked)):
            raise FigureError("a direction goal needs one origin column per axis")
        if self.wave is not None and (self.origin or len(self.tracked) != 2):
            raise FigureError("a wave goal tracks two axes (swing, height) and has no origin")
        if not self.radius > 0:
            raise FigureError(f"the goal radius must be positive, got {self.radius}")
        if not self.hold >= 0 or (self.hold and self.wave is not None):
            raise FigureError(f"a position or direction goal holds for 0 s or more (a wave has "
                              f"its own window), got {self.hold}")  # fmt: skip


@dataclass(frozen=True)
class Duck:
    """A bar to pass under, for the ``duck`` term: how far the top of the figure stands
    above the bar's underside while the figure is still before the bar.

    Attributes:
        points: the figure's high points as (sensor column of the height, e.g. ``z_elbow``;
            how far its surface reaches above it, m: the radius of the capsule ending there).
            The top is the highest point plus its reach (a capsule's top is one of its ends'
            plus its radius).
        height: the bar's underside, m.
        along: the sensor column of the root's position along the path, e.g. ``root_x``.
        at: where the bar is along it, m; the root is before the bar while it has not
            passed this from the start (0) on.
    """

    points: tuple[tuple[str, float], ...]
    height: float
    along: str
    at: float

    def __post_init__(self) -> None:
        if not self.points or not self.at:
            raise FigureError("a bar to duck under needs high points and a place off the start")


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
        low: ... or while a sensor column reads less than a value, e.g. ``("z_shade",
            0.2)``: a lamp whose shade is under 20 cm is lying down, or None.
        duck: the bar the ``duck`` term measures ducking under, or None.
        aim: a joint no controller drives that a fixed rule turns to face the goal
            (`sinews.figures.aim`), or None.
        params: what the task was built with (for configs and titles).
        music: the music terminals the controller hears after the sensors and the goal's
            (see `sinews.control.music_input`; a dance's); their values follow the
            figure's sensor columns in the controller's input rows.
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
    music: tuple[str, ...] = ()
    low: tuple[str, float] | None = None
    duck: Duck | None = None
    aim: Aim | None = None

    def __post_init__(self) -> None:
        unknown = [t for t in self.weights if t not in TERMS]
        if unknown or next(iter(self.weights), None) not in MAIN_GOALS:
            raise FigureError(f"{self.name}: weights must start with {' or '.join(MAIN_GOALS)} "
                              f"and use {TERMS}")  # fmt: skip
        low = () if self.low is None else (self.low[0],)
        duck = () if self.duck is None else (*(c for c, _ in self.duck.points), self.duck.along)
        aim = () if self.aim is None else (self.aim.angle, self.aim.ahead, self.aim.left)
        if "duck" in self.weights and self.duck is None:
            raise FigureError(f"{self.name}: the duck term needs a bar (Task.duck)")
        for column in (*self.sensors, *self.goal.tracked, *self.goal.target, *self.goal.origin,
                       *low, *duck, *aim):  # fmt: skip
            if isinstance(column, str):
                self.figure.sensor_index(column)
        if not 0 < self.seconds <= MAX_SECONDS:  # also refuses NaN
            raise FigureError(f"{self.name}: a trial lasts more than 0 and at most "
                              f"{MAX_SECONDS:g} s, got {self.seconds!r}")  # fmt: skip
        if not self.joints:
            raise FigureError(f"{self.name}: drive at least one joint")
        for joint in self.joints:
            if joint not in self.figure.joints:
                raise FigureError(f"{self.name}: the figure has no joint {joint!r}")
        if self.aim is not None and (
            self.aim.joint not in self.figure.joints or self.aim.joint in self.joints
        ):
            raise FigureError(f"{self.name}: the aimed joint must be one no controller drives")

    @property
    def terminals(self) -> tuple[str, ...]:
        """Names of the controller's input columns: the sensors, the goal-relative ones, the
        music's."""
        return (*self.sensors, *self.goal.names, *self.music)

    @property
    def actuators(self) -> npt.NDArray[np.intp]:
        """(J,) actuator index of each driven joint."""
        return np.array([self.figure.joints.index(j) for j in self.joints], dtype=np.intp)

    def input_map(self) -> tuple[FloatArray, FloatArray]:
        """The affine map from input columns to `terminals`: ``inputs @ W + b``.

        The inputs are the figure's S sensor columns, then the M music columns (none
        unless the task hears music).

        Returns:
            W: (S + M, V) weights.
            b: (V,) offsets.
        """
        index = self.figure.sensor_index
        n_sensors, n_music = self.figure.n_sensors, len(self.music)
        weights = np.zeros((n_sensors + n_music, len(self.terminals)))
        offset = np.zeros(len(self.terminals))
        for v, column in enumerate(self.sensors):
            weights[index(column), v] = 1.0
        for m in range(n_music):
            weights[n_sensors + m, len(self.terminals) - n_music + m] = 1.0
        first = len(self.sensors)
        named = zip(self.goal.tracked, self.goal.target, strict=True)  # the first axes
        for axis, (tracked, target) in enumerate(itertools.islice(named, len(self.goal.names))):
            weights[index(tracked), first + axis] -= 1.0
            if isinstance(target, str):
                weights[index(target), first + axis] += 1.0
            else:
                offset[first + axis] = float(target)
        return weights, offset


def dance_task(
    name: str,
    figure: Figure,
    joints: tuple[str, ...],
    sensors: tuple[str, ...],
    *,
    spot: tuple[str, ...],
    seconds: float,
    style: Mapping[str, float] = DANCE_STYLE,
    max_tilt: float = 1.0,
    min_height: float = -math.inf,
    low: tuple[str, float] | None = None,
) -> Task:
    """A dance of ``figure`` to the song: its ``joints``' motion must pause on the beats
    (``lift``), with ``style`` points (`DANCE_STYLE` unless a figure needs others, e.g. a
    snake that lies on the floor: no ``head`` or ``fallen``).

    The controller hears the song (`MUSIC_TERMINALS`) beside ``sensors``; ``spot``, the
    root's position columns (one per floor axis), must stay near their start, 0. The
    figure is down as `Task` says (``max_tilt``, ``min_height``, ``low``).
    """
    return Task(
        name=name,
        figure=figure,
        goal=Goal(tracked=spot, target=(0.0,) * len(spot), names=(), radius=0.1),
        joints=joints,
        sensors=sensors,
        weights={"lift": 1.0, **style},
        seconds=seconds,
        max_tilt=max_tilt,
        min_height=min_height,
        music=MUSIC_TERMINALS,
        low=low,
    )
