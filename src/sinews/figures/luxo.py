"""The Luxo lamp of Gritz & Hahn, in 2D: a base, two arm links and a head on three hinges.

Bodies ``base`` → ``arm_lower`` (hinge ``base_hinge``) → ``arm_upper`` (hinge
``elbow``) → ``head`` (hinge ``neck``). The arms are capsules, the base a flat
box and the head a thick capsule standing in for the shade. The MJCF lays the
lamp out in its rest pose, lower arm leaning back, upper arm forward, head
tipped down, so every hinge is at 0 when the lamp rests, and the whole lamp's
centre of mass sits over its base. Each hinge has a PD position servo, as in
the paper's "damped angular spring" towards a desired orientation.
"""

from __future__ import annotations

from dataclasses import dataclass

from sinews.figures.figure import Figure
from sinews.figures.mjcf import Servo, document, fmt, hinge, planar_root

__all__ = ["LuxoShape", "luxo", "luxo_mjcf"]


@dataclass(frozen=True)
class LuxoShape:
    """Dimensions (m), masses (kg), rest pose (rad), ranges and servos of the lamp.

    Attributes:
        base_half: half length and half height of the base box.
        arm_length: length of each arm link.
        head_length: length of the head capsule.
        arm_radius: radius of the arm capsules.
        head_radius: radius of the head capsule.
        masses: base, lower arm, upper arm, head.
        rest_angles: pitch of the lower arm from vertical, then the elbow's and the
            neck's relative pitch, in the rest pose (positive leans forward).
        joint_range: half-width of each hinge's range about its rest angle.
        servos: base hinge, elbow, neck.
    """

    base_half: tuple[float, float] = (0.1, 0.02)
    arm_length: float = 0.22
    head_length: float = 0.1
    arm_radius: float = 0.012
    head_radius: float = 0.035
    masses: tuple[float, float, float, float] = (0.6, 0.15, 0.15, 0.25)
    rest_angles: tuple[float, float, float] = (-0.4, 1.2, 1.4)
    joint_range: tuple[float, float, float] = (1.2, 1.5, 1.2)
    servos: tuple[Servo, Servo, Servo] = (
        Servo("base_hinge", kp=30.0, kv=1.5, torque=20.0),
        Servo("elbow", kp=20.0, kv=0.8, torque=15.0),
        Servo("neck", kp=5.0, kv=0.08, torque=5.0),
    )


def luxo_mjcf(shape: LuxoShape = LuxoShape(), *, friction: float = 1.0) -> str:
    """MJCF of the lamp resting on the floor (contact sensors are added by `luxo`)."""
    half_x, half_z = shape.base_half
    m_base, m_lower, m_upper, m_head = shape.masses
    a_lower, a_elbow, a_neck = shape.rest_angles
    r_base, r_elbow, r_neck = shape.joint_range
    length = shape.arm_length
    arm = f'type="capsule" size="{fmt(shape.arm_radius)}" fromto="0 0 0 0 0 {fmt(length)}"'
    head = (
        f'type="capsule" size="{fmt(shape.head_radius)}" '
        f'fromto="0 0 {fmt(shape.head_radius)} 0 0 {fmt(shape.head_length)}"'
    )
    body = f"""<body name="base" pos="0 0 {fmt(half_z)}">
      {planar_root()}
      <geom name="base" type="box" size="{fmt(half_x, 0.06, half_z)}" mass="{fmt(m_base)}"/>
      <body name="arm_lower" pos="0 0 {fmt(half_z)}" euler="0 {fmt(a_lower)} 0">
        {hinge("base_hinge", -r_base, r_base)}
        <geom name="arm_lower" {arm} mass="{fmt(m_lower)}"/>
        <body name="arm_upper" pos="0 0 {fmt(length)}" euler="0 {fmt(a_elbow)} 0">
          {hinge("elbow", -r_elbow, r_elbow)}
          <geom name="arm_upper" {arm} mass="{fmt(m_upper)}"/>
          <body name="head" pos="0 0 {fmt(length)}" euler="0 {fmt(a_neck)} 0">
            {hinge("neck", -r_neck, r_neck)}
            <geom name="head" {head} mass="{fmt(m_head)}"/>
          </body>
        </body>
      </body>
    </body>"""
    ranges = (r_base, r_elbow, r_neck)
    servos = [(servo, -r, r) for servo, r in zip(shape.servos, ranges, strict=True)]
    return document("luxo", body, servos, friction=friction)


def luxo(shape: LuxoShape = LuxoShape(), *, friction: float = 1.0) -> Figure:
    """The Luxo lamp as a `Figure`: base is ``base``, head is ``head``, the arms are limbs."""
    return Figure.from_mjcf(
        luxo_mjcf(shape, friction=friction),
        name="luxo",
        base_bodies=("base",),
        head_bodies=("head",),
        limb_bodies=("arm_lower", "arm_upper"),
    )
