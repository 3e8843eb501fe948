"""Pieces of MJCF shared by the figure builders: the document, the planar root, servos.

Every planar figure is one body tree on a floor plane. Its root body carries
three joints, ``root_x`` (slide along x), ``root_z`` (slide along z) and
``root_pitch`` (hinge about y), so the figure moves in the x-z plane with y as
the axis of every hinge. The figure's geoms collide with the floor only
(``contype=1 conaffinity=0`` against the floor's ``contype=0 conaffinity=1``),
so limbs pass through each other as in a 2D simulator.

A positive rotation about +y turns +z towards +x: a segment that points up
leans forward, one that hangs down swings backward.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

__all__ = ["ROOT_JOINTS", "Servo", "document", "fmt", "hinge", "planar_root"]

ROOT_JOINTS = ("root_x", "root_z", "root_pitch")
"""Names of the three joints of a planar root, in qpos order."""


def fmt(*values: float) -> str:
    """Numbers as an MJCF attribute value, e.g. ``fmt(0, 0.5)`` → ``"0 0.5"``."""
    return " ".join(f"{float(v):.9g}" for v in values)


@dataclass(frozen=True)
class Servo:
    """A PD position servo on one hinge: torque = kp·(target − q) − kv·q̇, clamped.

    Attributes:
        joint: name of the hinge it drives.
        kp: stiffness, N·m/rad.
        kv: damping, N·m·s/rad (integrated implicitly by ``implicitfast``).
        torque: the largest torque it can give, N·m.
    """

    joint: str
    kp: float
    kv: float
    torque: float

    def xml(self, lo: float, hi: float) -> str:
        """The ``<position>`` element; targets are clamped to the joint range ``[lo, hi]``."""
        return (
            f'<position name="{self.joint}" joint="{self.joint}" kp="{fmt(self.kp)}" '
            f'kv="{fmt(self.kv)}" ctrlrange="{fmt(lo, hi)}" '
            f'forcerange="{fmt(-self.torque, self.torque)}"/>'
        )


def hinge(name: str, lo: float, hi: float) -> str:
    """A limited hinge about y named ``name`` with range ``[lo, hi]`` radians."""
    return f'<joint name="{name}" type="hinge" axis="0 1 0" range="{fmt(lo, hi)}"/>'


def planar_root() -> str:
    """The root's three unlimited, undamped joints: slide x, slide z, hinge y."""
    axes = ("1 0 0", "0 0 1", "0 1 0")
    kinds = ("slide", "slide", "hinge")
    return "".join(
        f'<joint name="{name}" type="{kind}" axis="{axis}" limited="false" '
        'armature="0" damping="0"/>'
        for name, kind, axis in zip(ROOT_JOINTS, kinds, axes, strict=True)
    )


def document(
    model_name: str,
    root_body: str,
    servos: Sequence[tuple[Servo, float, float]],
    *,
    timestep: float = 0.001,
    friction: float = 1.0,
    joint_damping: float = 0.01,
    armature: float = 0.001,
) -> str:
    """A whole MJCF document: options, defaults, floor, one body tree and its servos.

    Args:
        model_name: the model's name.
        root_body: the XML of the root ``<body>`` (with `planar_root` joints).
        servos: (servo, lo, hi) for each actuated hinge, in actuator order.
        timestep: physics step, seconds (a rollout overrides it).
        friction: sliding friction coefficient of every contact.
        joint_damping: passive damping of the figure's hinges, N·m·s/rad.
        armature: rotor inertia added to each hinge, kg·m² (steadies light links).

    Returns:
        The MJCF XML string.
    """
    actuators = "\n    ".join(servo.xml(lo, hi) for servo, lo, hi in servos)
    return f"""<mujoco model="{model_name}">
  <compiler angle="radian" autolimits="true"/>
  <option timestep="{fmt(timestep)}" integrator="implicitfast"/>
  <default>
    <joint damping="{fmt(joint_damping)}" armature="{fmt(armature)}"/>
    <geom contype="1" conaffinity="0" condim="3" friction="{fmt(friction, 0.005, 0.0001)}"/>
  </default>
  <worldbody>
    <geom name="floor" type="plane" size="0 0 0.1" contype="0" conaffinity="1"/>
    {root_body}
  </worldbody>
  <actuator>
    {actuators}
  </actuator>
</mujoco>
"""
