"""A 3-segment planar snake: three capsules in a row on two hinges, lying on the floor.

Bodies ``tail`` ← (hinge ``waist``) ``middle`` → (hinge ``neck``) ``head``; the
middle segment is the root, so the snake is symmetric about it. At rest it lies
straight along x with every hinge at 0.
"""

from __future__ import annotations

from dataclasses import dataclass

from sinews.figures.figure import Figure
from sinews.figures.mjcf import Servo, document, fmt, hinge, planar_root

__all__ = ["SnakeShape", "snake", "snake_mjcf"]


@dataclass(frozen=True)
class SnakeShape:
    """Dimensions (m), masses (kg), ranges and servos of the snake.

    Attributes:
        segment_length: length of each capsule between hinges.
        radius: capsule radius.
        segment_mass: mass of each segment.
        joint_range: each hinge turns within ±this, rad.
        servos: waist (tail hinge), neck (head hinge).
    """

    segment_length: float = 0.3
    radius: float = 0.03
    segment_mass: float = 0.3
    joint_range: float = 1.5
    servos: tuple[Servo, Servo] = (
        Servo("waist", kp=5.0, kv=0.3, torque=5.0),
        Servo("neck", kp=5.0, kv=0.3, torque=5.0),
    )


def snake_mjcf(shape: SnakeShape = SnakeShape(), *, friction: float = 1.0) -> str:
    """MJCF of the snake lying straight on the floor (contact sensors added by `snake`)."""
    half = shape.segment_length / 2
    length = shape.segment_length
    geom = f'type="capsule" size="{fmt(shape.radius)}" mass="{fmt(shape.segment_mass)}"'
    r = shape.joint_range
    body = f"""<body name="middle" pos="0 0 {fmt(shape.radius)}">
      {planar_root()}
      <geom name="middle" {geom} fromto="{fmt(-half, 0, 0, half, 0, 0)}"/>
      <body name="tail" pos="{fmt(-half, 0, 0)}">
        {hinge("waist", -r, r)}
        <geom name="tail" {geom} fromto="{fmt(0, 0, 0, -length, 0, 0)}"/>
      </body>
      <body name="head" pos="{fmt(half, 0, 0)}">
        {hinge("neck", -r, r)}
        <geom name="head" {geom} fromto="{fmt(0, 0, 0, length, 0, 0)}"/>
      </body>
    </body>"""
    return document("snake", body, [(servo, -r, r) for servo in shape.servos], friction=friction)


def snake(shape: SnakeShape = SnakeShape(), *, friction: float = 1.0) -> Figure:
    """The snake as a `Figure`: base is ``tail`` and ``middle``, head is ``head``."""
    return Figure.from_mjcf(
        snake_mjcf(shape, friction=friction),
        name="snake",
        base_bodies=("tail", "middle"),
        head_bodies=("head",),
    )
