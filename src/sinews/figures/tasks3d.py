"""The 3D figures' motion tasks, as data (seed 003 in 3D): hop, limbo, point, wave, touch, nose,
dance.

Each builder returns a `sinews.figures.tasks.Task` like the planar ones: the
figure with its scene (a target is a **site in the world**, drawn by the
renderer and sensed like a hand: its place in the body's heading frame is a
sensor column), the goal, the driven joints (the rest hold the standing pose)
and the terminals.

"Terminals as in the paper": the lamp sees its joint angles, its height,
velocity (forward, sideways, up, in its heading frame), how its base leans,
the floor's force on the base, time, and the target in its heading frame
(``f_target`` ahead, ``l_target`` to the left) — "its position relative to
the goal point, its velocity, and the amount of force being imparted to its
base". The humanoid sees the driven joints' angles, both feet's floor forces,
its hand's position relative to the pelvis in the heading frame, time, and
the target relative to the hand in that frame (``gf``, ``gl``, ``gu``).
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from collections.abc import Callable, Mapping, Sequence
from typing import Any

from sinews.figures.aim import Aim
from sinews.figures.figure import Figure, FigureError
from sinews.figures.humanoid3d import humanoid3d
from sinews.figures.luxo3d import AIMED_LAMP, LuxoShape3D, luxo3d
from sinews.figures.mjcf import fmt
from sinews.figures.task import STYLE, TOUCH_HOLD, Goal, Task, Wave, dance_task, standing_height

__all__ = [
    "ARM_L",
    "ARM_R",
    "HUMANOID3D_DANCE",
    "LAMPS",
    "LUXO3D_JOINTS",
    "LUXO3D_SENSORS",
    "TASKS_3D",
    "humanoid3d_dance",
    "humanoid3d_gesture",
    "humanoid3d_nose",
    "humanoid3d_point",
    "humanoid3d_touch",
    "luxo3d_dance",
    "luxo3d_hop",
    "luxo3d_limbo",
]

LUXO3D_JOINTS = ("base_hinge", "elbow", "neck")
"""The 3D lamp's three servoed hinges (`sinews.figures.luxo3d`)."""
LUXO3D_BODY = (
    "time",
    *(f"q_{joint}" for joint in LUXO3D_JOINTS),
    "root_z",
    "root_vf",
    "root_vl",
    "root_vz",
    "root_lean_f",
    "root_lean_l",
    "fz_base",
)
"""What the 3D lamp senses of itself."""
LUXO3D_SENSORS = (*LUXO3D_BODY, "f_target", "l_target")
"""The 3D lamp's terminals (besides the constants): itself and the target."""

ARM_R = ("shoulder_x_r", "shoulder_y_r", "shoulder_z_r", "elbow_r")
"""The right arm's four hinges."""
ARM_L = ("shoulder_x_l", "shoulder_y_l", "shoulder_z_l", "elbow_l")
"""The left arm's four hinges."""

TARGET_RGBA = "0.85 0.15 0.15 1"


def _floor_mark(world: ET.Element, x: float, y: float) -> None:
    """A red X on the floor at (x, y) with the sensed site ``target`` at its centre."""
    ET.SubElement(world, "site", {"name": "target", "type": "cylinder", "pos": fmt(x, y, 0.001),
                                  "size": fmt(0.03, 0.001), "rgba": TARGET_RGBA})  # fmt: skip
    for angle in (math.pi / 4, -math.pi / 4):
        ET.SubElement(world, "site", {"type": "box", "pos": fmt(x, y, 0.001),
                                      "euler": fmt(0, 0, angle), "size": fmt(0.12, 0.012, 0.001),
                                      "rgba": TARGET_RGBA})  # fmt: skip


def _check_floor_target(name: str, target: Sequence[float]) -> tuple[float, float]:
    if len(target) != 2 or not all(math.isfinite(float(v)) for v in target):
        raise FigureError(f"{name}: the target is x,y in m, got {target!r}")
    x, y = float(target[0]), float(target[1])
    if not 0.3 <= math.hypot(x, y) <= 2.0:
        raise FigureError(f"{name}: the target must be 0.3 to 2 m from the start, got ({x}, {y})")
    return x, y


ON_THE_FLOOR = 0.0
"""The goal's ``root_z``: the base resting on the floor (``root_z`` is the base centre's height
above its rest pose's), so a lamp in mid-hop above the X at the end is not on it. From
2026-11-27 to 2026-11-29 this was the base's half height, 2 cm, read as a height above the
floor: the goal hung 2 cm above the resting base (docs/figures3d.md)."""


LAMPS: Mapping[str, LuxoShape3D] = {"twist": LuxoShape3D(), "aimed": AIMED_LAMP}
"""The 3D lamps a task can use: the twisting lamp (the default: the paper's 3 hinges, the neck
twisting the shade) and the aimed lamp (its swivel held facing the X by `SWIVEL_AIM`)."""
SWIVEL_AIM = Aim("swivel", angle="q_swivel", ahead="f_target", left="l_target")
"""The aimed lamp's rule: the swivel turns the arm's plane to face the X."""


def _lamp(name: str, lamp: str) -> tuple[Figure, Aim | None]:
    """The lamp called ``lamp`` (`LAMPS`) and the rule that aims it, if any."""
    if lamp not in LAMPS:
        raise FigureError(f"{name}: the lamp is {' or '.join(LAMPS)}, not {lamp!r}")
    shape = LAMPS[lamp]
    return luxo3d(shape), SWIVEL_AIM if shape.swivel else None


def _lamp_task(
    name: str,
    figure: Figure,
    target: tuple[float, float],
    weights: Mapping[str, float],
    seconds: float,
    params: Mapping[str, Any],
    aim: Aim | None,
) -> Task:
    return Task(
        name=name,
        figure=figure,
        goal=Goal(("root_x", "root_y", "root_z"), target=(*target, ON_THE_FLOOR), names=()),
        joints=LUXO3D_JOINTS,
        sensors=LUXO3D_SENSORS,
        weights=weights,
        seconds=seconds,
        params=params,
        aim=aim,
    )


def luxo3d_hop(
    target: Sequence[float] = (1.0, 0.5), *, seconds: float = 5.0, lamp: str = "twist"
) -> Task:
    """Hop to the X at (x, y) on the floor, 0.3–2 m from the start in any direction.

    The lamp (`LAMPS`) starts facing +x, so a target off the axis means turning as
    well as hopping (the aimed lamp's rule does the turning). The main goal is the
    base centre's distance from the X on the floor at the end (`ON_THE_FLOOR`); style as
    the planar lamp's (`STYLE`), and ``spot`` (the mean distance from the X over the
    trial: how soon it gets there) at weight 0 unless a run file weighs it
    (docs/figures3d.md).
    """
    x, y = _check_floor_target("luxo3d-hop", target)
    body, aim = _lamp("luxo3d-hop", lamp)
    root = ET.fromstring(body.xml)
    world = root.find("worldbody")
    assert world is not None
    _floor_mark(world, x, y)
    figure = _refigure(body, root, sites=("target",))
    return _lamp_task("luxo3d-hop", figure, (x, y), {"distance": 1.0, **STYLE, "spot": 0.0},
                      seconds, {"target": [x, y], "lamp": lamp}, aim)  # fmt: skip


LIMBO3D_SHARE = 0.8
"""The limbo bar's default height: this share of the lamp's standing height."""


def luxo3d_limbo(
    pole_height: float | None = None,
    *,
    target: Sequence[float] = (1.0, 0.0),
    pole_radius: float = 0.02,
    half_length: float = 1.5,
    seconds: float = 5.0,
    lamp: str = "twist",
) -> Task:
    """Limbo: hop to the X passing under a bar whose underside is ``pole_height`` m up.

    The bar lies across the straight path halfway to the X, ``2·half_length``
    long, with a board above it up to 1 m (so the lamp cannot hop over; it
    could walk round the 3 m bar, but that costs time and distance). Touching
    bar or board costs the ``touch`` term, weight 5 ("a large penalty for
    hitting his head on the limbo pole").
    """
    x, y = _check_floor_target("luxo3d-limbo", target)
    body, aim = _lamp("luxo3d-limbo", lamp)
    if pole_height is None:
        pole_height = round(LIMBO3D_SHARE * standing_height(body), 4)
    if not 0.0 < pole_height < 1.0:
        raise FigureError("luxo3d-limbo: the bar must be 0-1 m high")
    root = ET.fromstring(body.xml)
    world = root.find("worldbody")
    assert world is not None
    _floor_mark(world, x, y)
    height = pole_height + pole_radius
    across = math.atan2(y, x)  # the bar's body x axis points along the path
    pole = ET.SubElement(world, "body", {"name": "pole", "pos": fmt(x / 2, y / 2, height),
                                         "euler": fmt(0, 0, across)})  # fmt: skip
    collide = {"contype": "0", "conaffinity": "1", "rgba": "0.8 0.3 0.2 1"}
    ET.SubElement(pole, "geom", {"name": "pole", "type": "capsule", "size": fmt(pole_radius),
                                 "fromto": fmt(0, -half_length, 0, 0, half_length, 0),
                                 **collide})  # fmt: skip
    board = (1.0 - height - pole_radius) / 2
    ET.SubElement(pole, "geom", {"name": "board", "type": "box",
                                 "size": fmt(pole_radius / 2, half_length, board),
                                 "pos": fmt(0, 0, pole_radius + board),
                                 **collide, "rgba": "0.8 0.3 0.2 0.35"})  # fmt: skip
    figure = _refigure(body, root, sites=("target",), touch_bodies=("pole",))
    weights = {"distance": 1.0, **STYLE, "touch": 5.0}
    params = {"pole_height": pole_height, "target": [x, y], "lamp": lamp}
    return _lamp_task("luxo3d-limbo", figure, (x, y), weights, seconds, params, aim)


def luxo3d_dance(*, seconds: float = 10.0) -> Task:
    """Dance to the song with the three joints (`sinews.figures.task.dance_task`), near the
    spot on the floor (x, y); the lamp senses itself (`LUXO3D_BODY`) and hears the song."""
    return dance_task("luxo3d-dance", luxo3d(), LUXO3D_JOINTS, LUXO3D_BODY,
                      spot=("root_x", "root_y"), seconds=seconds)  # fmt: skip


def _refigure(
    figure: Figure,
    root: ET.Element,
    *,
    sites: tuple[str, ...] = (),
    touch_bodies: tuple[str, ...] = (),
) -> Figure:
    """``figure`` again from its edited MJCF (a 3D person's head feels only the floor: its
    own hand may touch it)."""
    head = figure.head_bodies if figure.name == "humanoid3d" else ()
    return figure.edited(root, sites=sites, touch_bodies=touch_bodies, floor_only=head)


# -- the humanoid --------------------------------------------------------------

PERSON_STYLE = {**STYLE, "neutral": 0.0, "still": 0.0}
"""The humanoid's style weights: the lamp's, without the neutral-pose bonus, and without
``still``: its goals are held (`TOUCH_HOLD`), which measures the staying (as in the planar
reach, where ``still`` ranked a hand that never came near above one that had)."""


def _person(target: Sequence[float] | None = None) -> Figure:
    """The humanoid with its hand, shoulder and nose sensed, and a target ball if given."""
    person = humanoid3d()
    root = ET.fromstring(person.xml)
    sites: tuple[str, ...] = ("hand_r", "shoulder_r", "nose")
    if target is not None:
        world = root.find("worldbody")
        assert world is not None
        ET.SubElement(world, "site", {"name": "target", "type": "sphere", "size": "0.03",
                                      "pos": fmt(*target), "rgba": TARGET_RGBA})  # fmt: skip
        sites += ("target",)
    return _refigure(person, root, sites=sites)


def _point3(name: str, target: Sequence[float]) -> tuple[float, float, float]:
    if len(target) != 3 or not all(math.isfinite(float(v)) for v in target):
        raise FigureError(f"{name}: the target is x,y,z in m, got {target!r}")
    x, y, z = (float(v) for v in target)
    if not (math.hypot(x, y) <= 5.0 and 0.0 <= z <= 3.0):
        raise FigureError(f"{name}: the target must be within 5 m and 0-3 m up, got {target!r}")
    return x, y, z


HAND = ("f_hand_r", "l_hand_r", "u_hand_r")
"""The right fingertips in the heading frame, relative to the pelvis."""


def _person_task(
    name: str,
    figure: Figure,
    goal: Goal,
    joints: tuple[str, ...],
    seconds: float,
    params: Mapping[str, Any],
    *,
    weights: Mapping[str, float] = PERSON_STYLE,
    extra: tuple[str, ...] = (),
) -> Task:
    return Task(
        name=name,
        figure=figure,
        goal=goal,
        joints=joints,
        sensors=("time", *(f"q_{j}" for j in joints), *extra, "fz_foot_l", "fz_foot_r", *HAND),
        weights={"distance": 1.0, **weights},
        seconds=seconds,
        max_tilt=0.5,
        min_height=-0.25,
        params=params,
    )


def humanoid3d_touch(
    target: Sequence[float] = (0.45, -0.25, 1.25), *, seconds: float = 3.0
) -> Task:
    """Touch a point (x, y, z) with the right fingertips (within 3 cm, held: the farthest
    over the last `TOUCH_HOLD` s), turning the trunk if needed: the right arm's four hinges
    and the waist's turn are driven (5)."""
    point = _point3("humanoid3d-touch", target)
    goal = Goal(tracked=HAND, target=("f_target", "l_target", "u_target"),
                names=("gf", "gl", "gu"), radius=0.03, hold=TOUCH_HOLD)  # fmt: skip
    return _person_task("humanoid3d-touch", _person(point), goal, (*ARM_R, "waist_z"), seconds,
                        {"target": list(point)})  # fmt: skip


def humanoid3d_point(target: Sequence[float] = (2.0, -1.5, 2.2), *, seconds: float = 3.0) -> Task:
    """Point the right arm at a point (x, y, z): the angle at the shoulder between the
    fingertips and the target, its largest over the last `TOUCH_HOLD` s, must be within
    5°. Driven: the right arm's four hinges and the waist's turn (5)."""
    point = _point3("humanoid3d-point", target)
    goal = Goal(tracked=HAND, target=("f_target", "l_target", "u_target"),
                names=("gf", "gl", "gu"), radius=math.radians(5.0), hold=TOUCH_HOLD,
                origin=("f_shoulder_r", "l_shoulder_r", "u_shoulder_r"))  # fmt: skip
    return _person_task("humanoid3d-point", _person(point), goal, (*ARM_R, "waist_z"), seconds,
                        {"target": list(point)})  # fmt: skip


def humanoid3d_gesture(
    rate: float = 1.5, *, amplitude: float = 0.1, window: float = 1.5, seconds: float = 4.0
) -> Task:
    """Wave: for the last ``window`` s the right hand is above the shoulder and swings
    sideways at ``rate`` Hz by at least ``amplitude`` m, about a point not inward of the
    shoulder (beside the head, not fanning the face). The right arm's four hinges are
    driven; the terminals add their rates (an oscillator needs them)."""
    wave = Wave(rate=float(rate), amplitude=float(amplitude), window=float(window),
                centre_at_most=0.0)  # fmt: skip
    if wave.window > seconds:
        raise FigureError("humanoid3d-gesture: the wave's window is longer than the trial")
    goal = Goal(tracked=("l_hand_r", "u_hand_r"), target=("l_shoulder_r", "u_shoulder_r"),
                names=("gl", "gu"), radius=1e-3, wave=wave)  # fmt: skip
    style = {"head": STYLE["head"], "fallen": STYLE["fallen"]}
    return _person_task(
        "humanoid3d-gesture", _person(), goal, ARM_R, seconds,
        {"rate": wave.rate, "amplitude": wave.amplitude, "window": wave.window},
        weights=style, extra=tuple(f"dq_{j}" for j in ARM_R),
    )  # fmt: skip


def humanoid3d_nose(*, seconds: float = 3.0) -> Task:
    """Put the right fingertips on the tip of the nose (within 3 cm, held over the last
    `TOUCH_HOLD` s): the right arm's four hinges and the neck's two are driven (6). The hand
    cannot pass into the head."""
    goal = Goal(tracked=HAND, target=("f_nose", "l_nose", "u_nose"), names=("gf", "gl", "gu"),
                radius=0.03, hold=TOUCH_HOLD)  # fmt: skip
    return _person_task("humanoid3d-nose", _person(), goal, (*ARM_R, "neck_y", "neck_z"),
                        seconds, {})  # fmt: skip


HUMANOID3D_DANCE = (*ARM_L, *ARM_R, "waist_z", "neck_y", "neck_z")
"""The 3D humanoid's dancing joints: both arms, the waist's turn and the neck (11); the legs
and the waist's bends hold the standing pose."""


def humanoid3d_dance(*, seconds: float = 10.0) -> Task:
    """Dance with the arms, the waist's turn and the neck (`HUMANOID3D_DANCE`) on the spot
    (x, y); down as in the other tasks. It sees the driven angles, how the pelvis leans,
    both feet's floor forces, and hears the song."""
    sensors = ("time", *(f"q_{j}" for j in HUMANOID3D_DANCE), "root_lean_f", "root_lean_l",
               "fz_foot_l", "fz_foot_r")  # fmt: skip
    return dance_task("humanoid3d-dance", _person(), HUMANOID3D_DANCE, sensors,
                      spot=("root_x", "root_y"), seconds=seconds, max_tilt=0.5,
                      min_height=-0.25)  # fmt: skip


TASKS_3D: Mapping[str, Callable[..., Task]] = {
    "luxo3d-hop": luxo3d_hop,
    "luxo3d-limbo": luxo3d_limbo,
    "luxo3d-dance": luxo3d_dance,
    "humanoid3d-point": humanoid3d_point,
    "humanoid3d-gesture": humanoid3d_gesture,
    "humanoid3d-touch": humanoid3d_touch,
    "humanoid3d-nose": humanoid3d_nose,
    "humanoid3d-dance": humanoid3d_dance,
}
"""The 3D tasks by name (`sinews.figures.tasks.TASKS` holds them too)."""
