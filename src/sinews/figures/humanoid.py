"""A planar humanoid: pelvis, torso, head, two arms and two legs on 12 servoed hinges.

Bodies: ``pelvis`` (root) → ``torso`` (hinge ``waist``) → ``head`` (``neck``)
and ``upper_arm_{l,r}`` (``shoulder_{l,r}``) → ``forearm_{l,r}`` (``elbow_{l,r}``);
``pelvis`` → ``thigh_{l,r}`` (``hip_{l,r}``) → ``shin_{l,r}`` (``knee_{l,r}``) →
``foot_{l,r}`` (``ankle_{l,r}``). Left and right limbs are offset in y but move
in the same x-z plane and pass through each other. The rest pose (all hinges
at 0) is standing straight with arms down and flat feet pointing +x.

Signs (a positive angle turns +z towards +x): hip and shoulder > 0 swing the
limb backward, knee > 0 bends the knee, elbow < 0 bends the elbow forward,
ankle > 0 points the toes down, waist > 0 leans the torso forward.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from sinews.figures.figure import Figure
from sinews.figures.mjcf import Servo, document, fmt, hinge, planar_root

__all__ = ["HumanoidShape", "humanoid", "humanoid_mjcf"]

LIMBS = ("pelvis", "torso", "upper_arm_l", "forearm_l", "upper_arm_r", "forearm_r",
         "thigh_l", "shin_l", "thigh_r", "shin_r")  # fmt: skip
"""Everything but the feet and the head: on the floor, the person is down."""


@dataclass(frozen=True)
class Joint:
    """Range (rad) and servo gains of one kind of joint (left and right share them)."""

    lo: float
    hi: float
    kp: float
    kv: float
    torque: float


@dataclass(frozen=True)
class HumanoidShape:
    """Dimensions (m), masses (kg) and joints of the humanoid (about 1.75 m, 62 kg).

    Attributes:
        thigh, shin, upper_arm, forearm: (length, radius, mass) of each capsule.
        torso: (length, radius, mass) of the torso capsule, upward from the waist.
        pelvis: (half width, radius, mass) of the pelvis capsule across y.
        head: (radius, mass) of the head sphere.
        foot: (heel, toe, height, mass): the sole runs from ``-heel`` to ``toe`` in x
            under the ankle, which sits ``height`` above the floor.
        hip_width, shoulder_width: y offset of each leg and arm.
        joints: range and servo of each joint kind, by kind name.
    """

    thigh: tuple[float, float, float] = (0.42, 0.06, 7.0)
    shin: tuple[float, float, float] = (0.42, 0.045, 3.5)
    upper_arm: tuple[float, float, float] = (0.28, 0.04, 2.0)
    forearm: tuple[float, float, float] = (0.27, 0.035, 1.5)
    torso: tuple[float, float, float] = (0.42, 0.1, 22.0)
    pelvis: tuple[float, float, float] = (0.1, 0.08, 8.0)
    head: tuple[float, float] = (0.1, 4.0)
    foot: tuple[float, float, float, float] = (0.07, 0.17, 0.06, 1.0)
    hip_width: float = 0.09
    shoulder_width: float = 0.18
    joints: tuple[tuple[str, Joint], ...] = (
        ("waist", Joint(-0.5, 1.5, kp=600.0, kv=40.0, torque=300.0)),
        ("neck", Joint(-0.7, 0.7, kp=50.0, kv=3.0, torque=30.0)),
        ("shoulder", Joint(-3.0, 1.0, kp=80.0, kv=5.0, torque=80.0)),
        ("elbow", Joint(-2.5, 0.05, kp=50.0, kv=3.0, torque=50.0)),
        ("hip", Joint(-2.0, 0.6, kp=600.0, kv=40.0, torque=300.0)),
        ("knee", Joint(-0.05, 2.4, kp=600.0, kv=30.0, torque=300.0)),
        ("ankle", Joint(-0.7, 0.9, kp=500.0, kv=20.0, torque=200.0)),
    )


def _capsule_down(name: str, size: tuple[float, float, float]) -> str:
    length, radius, mass = size
    return (
        f'<geom name="{name}" type="capsule" size="{fmt(radius)}" '
        f'fromto="0 0 0 0 0 {fmt(-length)}" mass="{fmt(mass)}"/>'
    )


def _chain(links: Sequence[tuple[str, str, str, str]]) -> str:
    """Nested bodies from (body, joint XML, pos, geom XML), outermost first."""
    if not links:
        return ""
    body, joint, pos, geom = links[0]
    inner = _chain(links[1:])
    return f'<body name="{body}" pos="{pos}">{joint}{geom}{inner}</body>'


def humanoid_mjcf(shape: HumanoidShape = HumanoidShape(), *, friction: float = 1.0) -> str:
    """MJCF of the humanoid standing on the floor (contact sensors added by `humanoid`)."""
    kinds = dict(shape.joints)

    def joint(kind: str, side: str = "") -> str:
        spec = kinds[kind]
        return hinge(kind + side, spec.lo, spec.hi)

    heel, toe, height, foot_mass = shape.foot
    foot = (
        f'<geom type="box" size="{fmt((heel + toe) / 2, 0.05, height / 2)}" '
        f'pos="{fmt((toe - heel) / 2, 0, -height / 2)}" mass="{fmt(foot_mass)}"'
    )
    legs, arms = [], []
    for side, sign in (("_l", 1.0), ("_r", -1.0)):
        legs.append(
            _chain(
                [
                    (
                        f"thigh{side}",
                        joint("hip", side),
                        fmt(0, sign * shape.hip_width, 0),
                        _capsule_down(f"thigh{side}", shape.thigh),
                    ),
                    (
                        f"shin{side}",
                        joint("knee", side),
                        fmt(0, 0, -shape.thigh[0]),
                        _capsule_down(f"shin{side}", shape.shin),
                    ),
                    (
                        f"foot{side}",
                        joint("ankle", side),
                        fmt(0, 0, -shape.shin[0]),
                        f'{foot} name="foot{side}"/>',
                    ),
                ]
            )
        )
        arms.append(
            _chain(
                [
                    (
                        f"upper_arm{side}",
                        joint("shoulder", side),
                        fmt(0, sign * shape.shoulder_width, shape.torso[0]),
                        _capsule_down(f"upper_arm{side}", shape.upper_arm),
                    ),
                    (
                        f"forearm{side}",
                        joint("elbow", side),
                        fmt(0, 0, -shape.upper_arm[0]),
                        _capsule_down(f"forearm{side}", shape.forearm),
                    ),
                ]
            )
        )
    torso_length, torso_radius, torso_mass = shape.torso
    pelvis_half, pelvis_radius, pelvis_mass = shape.pelvis
    head_radius, head_mass = shape.head
    hip_height = height + shape.shin[0] + shape.thigh[0]
    body = f"""<body name="pelvis" pos="0 0 {fmt(hip_height)}">
      {planar_root()}
      <geom name="pelvis" type="capsule" size="{fmt(pelvis_radius)}"
            fromto="{fmt(0, -pelvis_half, 0, 0, pelvis_half, 0)}" mass="{fmt(pelvis_mass)}"/>
      <body name="torso" pos="0 0 {fmt(pelvis_radius)}">
        {joint("waist")}
        <geom name="torso" type="capsule" size="{fmt(torso_radius)}"
              fromto="0 0 {fmt(torso_radius)} 0 0 {fmt(torso_length)}" mass="{fmt(torso_mass)}"/>
        <body name="head" pos="0 0 {fmt(torso_length + torso_radius)}">
          {joint("neck")}
          <geom name="head" type="sphere" size="{fmt(head_radius)}"
                pos="0 0 {fmt(head_radius)}" mass="{fmt(head_mass)}"/>
        </body>
        {arms[0]}{arms[1]}
      </body>
      {legs[0]}{legs[1]}
    </body>"""
    order = ("waist", "neck", "shoulder", "elbow", "shoulder", "elbow",
             "hip", "knee", "ankle", "hip", "knee", "ankle")  # fmt: skip
    sides = ("", "", "_l", "_l", "_r", "_r", "_l", "_l", "_l", "_r", "_r", "_r")
    servos = []
    for kind, side in zip(order, sides, strict=True):
        spec = kinds[kind]
        servos.append((Servo(kind + side, spec.kp, spec.kv, spec.torque), spec.lo, spec.hi))
    return document("humanoid", body, servos, friction=friction)


def humanoid(shape: HumanoidShape = HumanoidShape(), *, friction: float = 1.0) -> Figure:
    """The humanoid as a `Figure`: feet are ``foot_l``, ``foot_r``; head is ``head``."""
    return Figure.from_mjcf(
        humanoid_mjcf(shape, friction=friction),
        name="humanoid",
        base_bodies=("foot_l", "foot_r"),
        head_bodies=("head",),
        limb_bodies=LIMBS,
    )
