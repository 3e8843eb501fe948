"""The built-in motion tasks (hop to an X, limbo, reach) and `make_task`.

Gritz & Hahn rate a motion by a main goal ("the distance between the figure
and the X at the end of the time allotment") plus style points. A `Task`
(in `sinews.figures.task`) holds all of that for one task; `TaskMeter` (in
`sinews.figures.terms`) measures every term for a whole population from the
rollout's per-tick sensors. The engine has no special cases: a limbo pole is
an extra body in the MJCF with a contact sensor, a hand is a site with a
position sensor, a goal is a tracked point and a target, and goal-relative
terminals such as ``gx = X − root_x`` are an affine map of the sensor columns
(`Task.input_map`).

The terms (`TERMS`) are higher-is-better, as `sinews.evolve.fitness` expects;
a task weighs them. `Goal`, `Task`, `TERMS` and `TaskMeter` are re-exported
here for callers that import them with the tasks.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from collections.abc import Callable, Mapping
from typing import Any

from sinews.figures.figure import Figure, FigureError
from sinews.figures.humanoid import humanoid
from sinews.figures.luxo import LuxoShape, luxo
from sinews.figures.mjcf import fmt
from sinews.figures.snake import snake
from sinews.figures.task import (
    DANCE_STYLE,
    STYLE,
    TERMS,
    TOUCH_HOLD,
    Duck,
    Goal,
    Task,
    Wave,
    dance_task,
    standing_height,
)
from sinews.figures.tasks3d import TASKS_3D
from sinews.figures.terms import TaskMeter

__all__ = [
    "DANCE_STYLE",
    "LIMBO_BOARD_TOP",
    "LIMBO_SHARE",
    "LUXO_LYING",
    "STYLE",
    "TASKS",
    "TERMS",
    "TOUCH",
    "TOUCH_HOLD",
    "Goal",
    "Task",
    "TaskMeter",
    "Wave",
    "dance_task",
    "humanoid_dance",
    "humanoid_reach",
    "luxo_dance",
    "luxo_hop",
    "luxo_limbo",
    "make_task",
    "on_the_x",
    "snake_dance",
    "standing_height",
]


# -- the built-in tasks --------------------------------------------------------

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


def on_the_x(target: float) -> Goal:
    """The lamp's base on the floor at x = ``target``: the distance counts the base centre's
    height above its rest too, so a lamp in mid-hop over the X at the end is not on it
    (until 2026-11-27 it counted x alone). Only x has a terminal, ``gx``."""
    return Goal(tracked=("root_x", "root_z"), target=(float(target), 0.0), names=("gx",))


def luxo_hop(target: float = 1.0, *, seconds: float = 5.0) -> Task:
    """Hop to the X: the lamp's base must end on the floor at ``target`` m along x (0.5–2 m
    ahead or behind; `on_the_x`)."""
    if not 0.5 <= abs(target) <= 2.0:
        raise FigureError(f"luxo-hop: the target must be 0.5 to 2 m ahead or behind, got {target}")
    return Task(
        name="luxo-hop",
        figure=luxo(),
        goal=on_the_x(target),
        joints=("base_hinge", "elbow", "neck"),
        sensors=LUXO_SENSORS,
        weights={"distance": 1.0, **STYLE},
        seconds=seconds,
        params={"target": float(target)},
    )


LUXO_LYING = 0.2
"""A dancing lamp whose shade is lower than this, m, is down (standing, it is at 0.40 m):
without it, a lamp lying on its side and beating its shade on the floor stayed "up"."""


def luxo_dance(*, seconds: float = 10.0) -> Task:
    """Dance to the song: the lamp's three joints' motion must pause on the beats, with
    style for staying up (its shade above `LUXO_LYING`), near where it started, using all
    three joints, smoothly (`dance_task`). The controller hears the song beside the hop's
    sensors."""
    figure = _with_sites(luxo(), {"shade": ("head", (0, 0, 0))})
    return dance_task("luxo-dance", figure, ("base_hinge", "elbow", "neck"), LUXO_SENSORS,
                      spot=("root_x",), seconds=seconds, low=("z_shade", LUXO_LYING))  # fmt: skip


def _with_sites(figure: Figure, sites: Mapping[str, tuple[str, tuple[float, ...]]]) -> Figure:
    """``figure`` with tracked sites: name → (body, position in the body's frame, m)."""
    root = ET.fromstring(figure.xml)
    for site, (body, pos) in sites.items():
        element = root.find(f".//body[@name='{body}']")
        assert element is not None
        ET.SubElement(element, "site", {"name": site, "pos": fmt(*pos), "size": "0.02"})
    return figure.edited(root, sites=tuple(sites))


HUMANOID_DANCE = ("neck", "shoulder_l", "elbow_l", "shoulder_r", "elbow_r")
"""The planar humanoid's dancing joints: the neck and arms; the legs and the waist hold the
standing pose (with the waist driven too, 34 of 40 random programs were down most of the
time; without it, 2 of 40)."""


def humanoid_dance(*, seconds: float = 10.0) -> Task:
    """Dance with the neck and arms (`HUMANOID_DANCE`) standing on the spot; the figure is down
    as in the reach (tilted over 0.5 rad, or the pelvis 0.25 m low). It sees the driven
    angles, its pitch and both feet's floor forces, and hears the song."""
    sensors = ("time", *(f"q_{j}" for j in HUMANOID_DANCE), "root_pitch", "fz_foot_l",
               "fz_foot_r")  # fmt: skip
    return dance_task("humanoid-dance", humanoid(), HUMANOID_DANCE, sensors, spot=("root_x",),
                      seconds=seconds, max_tilt=0.5, min_height=-0.25)  # fmt: skip


SNAKE_STYLE = {**DANCE_STYLE, "head": 0.0, "fallen": 0.0}
"""A snake's dance style: it lies on the floor, head down, so being down costs nothing."""


def snake_dance(*, seconds: float = 10.0) -> Task:
    """Dance with both hinges (waist and neck) lying on the floor, near the spot."""
    joints = ("waist", "neck")
    sensors = ("time", "q_waist", "q_neck", "root_vx", "fz_tail", "fz_middle", "fz_head")
    return dance_task("snake-dance", snake(), joints, sensors, spot=("root_x",),
                      seconds=seconds, style=SNAKE_STYLE)  # fmt: skip


LIMBO_SHARE = 0.8
"""The limbo pole's default height: this share of the lamp's standing height."""
LIMBO_BOARD_TOP = 1.0
"""Top of the board above the limbo bar, m: the lamp must pass under, not hop over."""


_SHAPE = LuxoShape()
LUXO_HIGH_POINTS = {
    "elbow": ("arm_upper", (0.0, 0.0, 0.0), _SHAPE.arm_radius),
    "neck": ("head", (0.0, 0.0, 0.0), _SHAPE.arm_radius),
    "shade_back": ("head", (0.0, 0.0, _SHAPE.head_radius), _SHAPE.head_radius),
    "shade": ("head", (0.0, 0.0, _SHAPE.head_length), _SHAPE.head_radius),
}
"""The ends of the lamp's upper capsules (site → body, position, the capsule's radius): in any
pose its top is one of them plus its radius. The limbo's ``duck`` term measures that top above
the bar (the lower arm's other end is at the base, below its elbow end or the base's top)."""
LUXO_TOPS = tuple((f"z_{site}", radius) for site, (*_, radius) in LUXO_HIGH_POINTS.items())
"""The heights of `LUXO_HIGH_POINTS` as a `Duck`'s points."""


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
    sites = {site: (body, pos) for site, (body, pos, _) in LUXO_HIGH_POINTS.items()}
    figure = _with_sites(lamp.edited(root, touch_bodies=("pole",)), sites)
    return Task(
        name="luxo-limbo",
        figure=figure,
        goal=on_the_x(target),
        joints=("base_hinge", "elbow", "neck"),
        sensors=LUXO_SENSORS,
        weights={"distance": 1.0, **STYLE, "touch": 5.0, "duck": 0.0},
        seconds=seconds,
        params={"pole_height": pole_height, "target": float(target), "pole_x": where},
        duck=Duck(LUXO_TOPS, pole_height, "root_x", where),
    )


TOUCH = 0.02
"""A hand touches its target within this, m: the reach's goal radius (the lamp's X is 0.05 m).
With 0.05 m, "settled early" (weight 0.2) outbid precision: a hand held 4.6 cm from the nose
from the first second outscored one that ended 1 cm from it a second later."""


def humanoid_reach(
    target: tuple[float, float] | str = (0.45, 1.3), *, seconds: float = 3.0
) -> Task:
    """Touch a point (x, z) in front of the figure with the right hand, or ``"nose"``: its nose.

    The controller drives the waist, neck, right shoulder and right elbow; the
    other joints hold the standing pose. It sees those angles, both feet's
    floor forces, its hand's position, time, and the hand-to-target vector
    (``gx``, ``gz``). The hand has arrived within `TOUCH`; the distance is the farthest
    it gets over the last `TOUCH_HOLD` seconds. Style: ``early``, ``head`` and ``fallen``.
    The hold measures staying, and ``still`` (path after the first pass within `TOUCH`)
    made a hand that once came near rank below one that never did: a nose best ended
    5.0 cm away with ``still`` 0 above a 3.7 cm hand that had passed the nose.
    """
    figure = _with_sites(humanoid(), {"hand_r": ("forearm_r", (0, 0, -0.305)),
                                      "nose": ("head", (0.1, 0, 0.1))})  # fmt: skip
    nose = target == "nose"
    if not nose and (isinstance(target, str) or len(target) != 2):
        raise FigureError(f"humanoid-reach: the target is 'nose' or x,z, got {target!r}")
    goal_at: tuple[float | str, ...] = ("x_nose", "z_nose") if nose else tuple(map(float, target))
    joints = ("waist", "neck", "shoulder_r", "elbow_r")
    return Task(
        name="humanoid-reach",
        figure=figure,
        goal=Goal(
            tracked=("x_hand_r", "z_hand_r"),
            target=goal_at,
            names=("gx", "gz"),
            radius=TOUCH,
            hold=TOUCH_HOLD,
        ),
        joints=joints,
        sensors=(
            "time",
            *(f"q_{j}" for j in joints),
            "fz_foot_l",
            "fz_foot_r",
            "x_hand_r",
            "z_hand_r",
        ),
        weights={"distance": 1.0, **STYLE, "still": 0.0, "neutral": 0.0},
        seconds=seconds,
        max_tilt=0.5,
        min_height=-0.25,
        params={"target": "nose" if nose else list(goal_at)},
    )


TASKS: Mapping[str, Callable[..., Task]] = {
    "luxo-hop": luxo_hop,
    "luxo-limbo": luxo_limbo,
    "luxo-dance": luxo_dance,
    "humanoid-reach": humanoid_reach,
    "humanoid-dance": humanoid_dance,
    "snake-dance": snake_dance,
    **TASKS_3D,
}
"""The built-in tasks by name: the planar ones and the 3D ones (`sinews.figures.tasks3d`)."""


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
