"""Pieces of MJCF shared by the 3D figure builders: the document, the free root, hinges.

A 3D figure is one body tree on a floor plane with a **free** root joint
(``root``: position and orientation, 6 degrees of freedom), so it can travel,
turn and tip over in any direction. Every other joint is a hinge with a PD
position servo (`sinews.figures.mjcf.Servo`). The floor is checkered and the
scene has a light, a sky and an offscreen buffer large enough for 1280×720
frames, so `sinews.render.mujoco_view` renders it as it is.

Collision classes (MuJoCo collides two geoms when ``contype`` of one meets
``conaffinity`` of the other):

- the floor: ``contype=0 conaffinity=1``;
- a figure's geoms by default: ``contype=1 conaffinity=0`` (the floor only);
- `TOUCHABLE` geoms (a person's head and trunk): ``contype=1 conaffinity=2``;
- `TOUCHING` geoms (a person's hands and forearms): ``contype=3 conaffinity=0``,
  so hands meet the floor and the touchable parts, and nothing else.
"""

from __future__ import annotations

from collections.abc import Sequence

from sinews.figures.mjcf import Servo, fmt

__all__ = ["FREE_ROOT", "TOUCHABLE", "TOUCHING", "document3d", "hinge3d"]

FREE_ROOT = '<freejoint name="root"/>'
"""The root's free joint (position x, y, z and a quaternion)."""

TOUCHABLE = 'contype="1" conaffinity="2"'
"""Geom attributes of parts a hand can touch (and that rest on the floor)."""

TOUCHING = 'contype="3" conaffinity="0"'
"""Geom attributes of parts that touch the floor and the touchable parts."""


def hinge3d(name: str, axis: Sequence[float], lo: float, hi: float) -> str:
    """A limited hinge named ``name`` about ``axis`` (body frame) with range ``[lo, hi]`` rad."""
    return f'<joint name="{name}" type="hinge" axis="{fmt(*axis)}" range="{fmt(lo, hi)}"/>'


def document3d(
    model_name: str,
    root_body: str,
    servos: Sequence[tuple[Servo, float, float]],
    *,
    timestep: float = 0.001,
    friction: float = 1.0,
    joint_damping: float = 0.01,
    armature: float = 0.002,
    extent: float = 2.0,
) -> str:
    """A whole 3D MJCF document: options, visuals, floor, one body tree and its servos.

    Args:
        model_name: the model's name.
        root_body: the XML of the root ``<body>`` (with `FREE_ROOT` first).
        servos: (servo, lo, hi) for each actuated hinge, in actuator order.
        timestep: physics step, seconds (a rollout overrides it).
        friction: sliding friction coefficient of every contact.
        joint_damping: passive damping of the figure's hinges, N·m·s/rad.
        armature: rotor inertia added to each hinge, kg·m².
        extent: the scene's size for the renderer's clipping planes and lights, m.

    Returns:
        The MJCF XML string.
    """
    actuators = "\n    ".join(servo.xml(lo, hi) for servo, lo, hi in servos)
    return f"""<mujoco model="{model_name}">
  <compiler angle="radian" autolimits="true"/>
  <option timestep="{fmt(timestep)}" integrator="implicitfast"/>
  <statistic extent="{fmt(extent)}" center="0 0 0.5"/>
  <visual>
    <global offwidth="1280" offheight="720"/>
    <quality shadowsize="1024"/>
    <headlight ambient="0.35 0.35 0.35" diffuse="0.5 0.5 0.5" specular="0.1 0.1 0.1"/>
  </visual>
  <asset>
    <texture name="sky" type="skybox" builtin="gradient" rgb1="0.75 0.82 0.9" rgb2="0.95 0.96 0.98"
             width="256" height="256"/>
    <texture name="grid" type="2d" builtin="checker" rgb1="0.86 0.86 0.84" rgb2="0.74 0.74 0.72"
             width="512" height="512"/>
    <material name="floor" texture="grid" texrepeat="10 10" texuniform="true"/>
    <material name="figure" rgba="0.93 0.6 0.25 1"/>
    <material name="accent" rgba="0.3 0.45 0.75 1"/>
  </asset>
  <default>
    <joint damping="{fmt(joint_damping)}" armature="{fmt(armature)}"/>
    <geom contype="1" conaffinity="0" condim="3" friction="{fmt(friction, 0.005, 0.0001)}"
          material="figure"/>
    <site group="2"/>
  </default>
  <worldbody>
    <light name="sun" pos="0 0 6" dir="0 0.2 -1" directional="true" castshadow="true"
           diffuse="0.6 0.6 0.6"/>
    <geom name="floor" type="plane" size="0 0 0.1" contype="0" conaffinity="1" material="floor"/>
    {root_body}
  </worldbody>
  <actuator>
    {actuators}
  </actuator>
</mujoco>
"""
