"""The Luxo lamp of Gritz & Hahn in 3D: 4 links, 3 servoed hinges, a free base.

"Our lamp model was a fully 3-dimensional articulated body with 4 links and 3
internally controllable degrees of freedom." Bodies: ``base`` (a disc, with
the free root joint, so it slides, turns and tips in any direction) →
``arm_lower`` (hinge ``base_hinge``, pitch) → ``arm_upper`` (hinge ``elbow``,
pitch) → ``head`` (hinge ``neck``).

The paper does not say where its three axes point. With three parallel
pitch axes (the planar lamp's) a lamp standing symmetric can never turn: no
torque about the vertical ever arises. Here the two arm hinges pitch (they make
the hop) and the **neck twists the shade about the upper arm's axis**, as a
desk lamp's shade swivels: swinging the heavy head off the lamp's plane moves
its centre of mass sideways and, through the tilted arm, gives a reaction
about the vertical, so hops can veer and turn (measured in docs/figures3d.md).

Two other lamps, for comparison: ``neck_axis="pitch"``, the planar lamp's
neck, and the **swivel lamp** ``LuxoShape3D(swivel=True, neck_axis="fixed")``:
the lower arm turns on the base about the vertical (hinge ``swivel``, a
gentle servo: a 3 rad step turns the arm in ~0.5 s without tipping the lamp),
the shade is fixed, and the heading frame follows the arm (the figure's
``heading_joint``). It did not hop to the X more often than the twisting lamp
(docs/figures3d.md, session 11), so it is not the default. The **aimed lamp**
(`AIMED_LAMP`: the pitch neck and a full-turn swivel that a fixed rule, not a
program, keeps facing the X) is the one that reaches off-axis targets
(docs/figures3d.md, session 28); it has four hinges, so it is not the default either.

At rest every hinge is at 0, the lower arm leans back, the upper arm forward,
the head points down and forward (the planar lamp's pose), and the heading
(the base's x axis) points where the lamp looks.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from sinews.figures.figure import Figure
from sinews.figures.mjcf import Servo, fmt
from sinews.figures.mjcf3d import FREE_ROOT, document3d, hinge3d

__all__ = ["AIMED_LAMP", "LuxoShape3D", "luxo3d", "luxo3d_mjcf"]


SWIVEL_SERVO = Servo("swivel", kp=2.0, kv=0.5, torque=1.0)
"""The swivel's servo: critically damped on the arm's ~0.03 kg·m² about the vertical, and
weak enough that a 3 rad step turns the arm in ~0.5 s without tipping the lamp."""


@dataclass(frozen=True)
class LuxoShape3D:
    """Dimensions (m), masses (kg), rest pose (rad), ranges and servos of the 3D lamp.

    Attributes:
        base_radius: radius of the base disc.
        base_half_height: half its thickness.
        arm_length: length of each arm link.
        head_length: length of the head capsule.
        arm_radius: radius of the arm capsules.
        head_radius: radius of the head capsule.
        masses: base, lower arm, upper arm, head.
        rest_angles: pitch of the lower arm from vertical, then the elbow's and
            the neck's relative pitch, in the rest pose (positive leans forward).
        joint_range: half-width of each hinge's range about its rest angle.
        neck_axis: the neck's hinge: ``"twist"`` (about the upper arm, the
            default), ``"pitch"`` or ``"fixed"`` (none).
        swivel: whether the lower arm turns on the base (hinge ``swivel``, the
            first servo, and the heading joint).
        swivel_range: half-width of the swivel's range, rad.
        swivel_servo: its servo.
        servos: base hinge, elbow, neck (the neck's unused when it is fixed).
    """

    base_radius: float = 0.1
    base_half_height: float = 0.02
    arm_length: float = 0.22
    head_length: float = 0.1
    arm_radius: float = 0.012
    head_radius: float = 0.035
    masses: tuple[float, float, float, float] = (0.6, 0.15, 0.15, 0.25)
    rest_angles: tuple[float, float, float] = (-0.4, 1.2, 1.4)
    joint_range: tuple[float, float, float] = (1.2, 1.5, 1.2)
    neck_axis: str = "twist"
    swivel: bool = False
    swivel_range: float = 2.8
    swivel_servo: Servo = SWIVEL_SERVO
    servos: tuple[Servo, Servo, Servo] = (
        Servo("base_hinge", kp=30.0, kv=1.5, torque=20.0),
        Servo("elbow", kp=20.0, kv=0.8, torque=15.0),
        Servo("neck", kp=5.0, kv=0.08, torque=5.0),
    )


AIMED_LAMP = LuxoShape3D(neck_axis="pitch", swivel=True, swivel_range=math.tau)
"""The **aimed lamp**: the planar lamp's three pitch hinges (which make the hop) on a swivel
that turns a full turn either way. No program drives the swivel: a fixed rule holds the arm's
plane facing the X (`sinews.figures.tasks3d.SWIVEL_AIM`), as the paper's humanoid held its
other joints "under simple dynamic control"."""


def luxo3d_mjcf(shape: LuxoShape3D = LuxoShape3D(), *, friction: float = 1.0) -> str:
    """MJCF of the 3D lamp resting on the floor (contact sensors are added by `luxo3d`)."""
    m_base, m_lower, m_upper, m_head = shape.masses
    a_lower, a_elbow, a_neck = shape.rest_angles
    r_base, r_elbow, r_neck = shape.joint_range
    length, half = shape.arm_length, shape.base_half_height
    arm = f'type="capsule" size="{fmt(shape.arm_radius)}" fromto="0 0 0 0 0 {fmt(length)}"'
    head = (
        f'type="capsule" size="{fmt(shape.head_radius)}" '
        f'fromto="0 0 {fmt(shape.head_radius)} 0 0 {fmt(shape.head_length)}"'
    )
    if shape.neck_axis == "twist":
        # the head body sits on the arm's axis, the twist turns it about that axis, and the
        # shade is pitched inside it by the rest angle
        neck = hinge3d("neck", (0, 0, 1), -r_neck, r_neck)
        head_body = f"""<body name="head" pos="0 0 {fmt(length)}">
            {neck}
            <geom name="head" {head} mass="{fmt(m_head)}" euler="0 {fmt(a_neck)} 0"
                  material="accent"/>
          </body>"""
    elif shape.neck_axis == "fixed":
        head_body = f"""<body name="head" pos="0 0 {fmt(length)}" euler="0 {fmt(a_neck)} 0">
            <geom name="head" {head} mass="{fmt(m_head)}" material="accent"/>
          </body>"""
    elif shape.neck_axis == "pitch":
        neck = hinge3d("neck", (0, 1, 0), -r_neck, r_neck)
        head_body = f"""<body name="head" pos="0 0 {fmt(length)}" euler="0 {fmt(a_neck)} 0">
            {neck}
            <geom name="head" {head} mass="{fmt(m_head)}" material="accent"/>
          </body>"""
    else:
        raise ValueError(f"neck_axis is 'fixed', 'twist' or 'pitch', not {shape.neck_axis!r}")
    swivel = ""
    if shape.swivel:
        # the first of the lower arm's two joints turns it about the base's vertical (the body
        # frame leans by the rest pitch, so the axis is the vertical seen from that frame)
        up = (-math.sin(a_lower), 0.0, math.cos(a_lower))
        swivel = hinge3d("swivel", up, -shape.swivel_range, shape.swivel_range) + "\n        "
    body = f"""<body name="base" pos="0 0 {fmt(half)}">
      {FREE_ROOT}
      <geom name="base" type="cylinder" size="{fmt(shape.base_radius, half)}"
            mass="{fmt(m_base)}" material="accent"/>
      <site name="base_front" pos="{fmt(shape.base_radius * 0.8, 0, half)}" size="0.012"
            rgba="0.1 0.1 0.1 1"/>
      <body name="arm_lower" pos="0 0 {fmt(half)}" euler="0 {fmt(a_lower)} 0">
        {swivel}{hinge3d("base_hinge", (0, 1, 0), -r_base, r_base)}
        <geom name="arm_lower" {arm} mass="{fmt(m_lower)}"/>
        <body name="arm_upper" pos="0 0 {fmt(length)}" euler="0 {fmt(a_elbow)} 0">
          {hinge3d("elbow", (0, 1, 0), -r_elbow, r_elbow)}
          <geom name="arm_upper" {arm} mass="{fmt(m_upper)}"/>
          {head_body}
        </body>
      </body>
    </body>"""
    ranges = (r_base, r_elbow, r_neck)
    servos = [(servo, -r, r) for servo, r in zip(shape.servos, ranges, strict=True)]
    if shape.neck_axis == "fixed":
        servos = servos[:2]
    if shape.swivel:
        servos.insert(0, (shape.swivel_servo, -shape.swivel_range, shape.swivel_range))
    return document3d("luxo3d", body, servos, friction=friction, extent=1.5)


def luxo3d(shape: LuxoShape3D = LuxoShape3D(), *, friction: float = 1.0) -> Figure:
    """The 3D lamp as a `Figure` (free root): base ``base``, head ``head``, the arms limbs."""
    return Figure.from_mjcf(
        luxo3d_mjcf(shape, friction=friction),
        name="luxo3d",
        base_bodies=("base",),
        head_bodies=("head",),
        limb_bodies=("arm_lower", "arm_upper"),
        root="free",
        heading_joint="swivel" if shape.swivel else None,
    )
