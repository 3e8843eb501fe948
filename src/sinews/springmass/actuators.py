"""Actuators: force rules on single nodes, driven by a shared table of signals.

An actuator sits on one node and reads a contiguous range of *channels* of a
drive table (S steps x C channels, values >= 0, shared by the whole batch).
Its drive at a step is the largest value in its range, so it can never react
to a channel outside its range. The engine knows nothing of music: dance
responders (`sinews.dancers.responders`) map bands of a song onto channels.

Kinds (``a`` = drive, ``s`` = strength in newtons, ``c`` = custom in [0, 1],
``r`` = node position minus the body's centroid):

- PUSH: ``s a`` along the angle ``2 pi c`` (a kick in a fixed direction).
- BOB: down while the drive is fresh (the first ``0.15 + 0.35 c`` of its decay),
  then up: an anticipating squash-and-jump.
- SPIN: ``s a`` perpendicular to ``r``, clockwise for ``c < 0.5``.
- REACH: ``s a`` outward along ``r``, bent toward straight up by ``c``.
- SHAKE: ``s a cos(4 pi phase)`` along the angle ``pi c / 2`` (sideways for c = 0,
  up and down for c = 1): two cycles per cycle of the phase signal.
- SWAY: ``s a cos(2 pi phase)`` sideways (mirrored for ``c >= 0.5``), one cycle per
  cycle of the phase signal.

Dancers feed a phase signal that runs once per two beats (`sinews.dancers.responders`),
so a sway goes left on one beat and right on the next and a shake turns on every
beat: their force peaks, and so the body's turning points, fall on the beats.
- PULSE: pushes every neighbour away along its edge (``c >= 0.5``) or pulls it
  in (``c < 0.5``) with ``s a``, the node taking the reaction: the node's
  springs breathe.
"""

from __future__ import annotations

from enum import IntEnum

import numpy as np
from numba import njit

__all__ = ["ActuatorKind", "actuator_force"]


class ActuatorKind(IntEnum):
    """Codes of the actuator force patterns."""

    PUSH = 0
    BOB = 1
    SPIN = 2
    REACH = 3
    SHAKE = 4
    SWAY = 5
    PULSE = 6


_PUSH, _BOB, _SPIN, _REACH, _SHAKE, _SWAY = 0, 1, 2, 3, 4, 5
_TAU = 2.0 * np.pi


@njit(cache=True, inline="always")
def actuator_force(kind, drive, strength, custom, rx, ry, t, phase):
    """Force (fx, fy) of a point actuator (every kind but PULSE).

    Args:
        kind: `ActuatorKind` code.
        drive: the actuator's drive, >= 0.
        strength: newtons at drive 1.
        custom: the kind's tuning value in [0, 1].
        rx, ry: node position minus the body's centroid, metres.
        t: seconds since the start.
        phase: the phase signal in [0, 1) at this step.
    """
    magnitude = strength * drive
    if kind == _PUSH:
        return magnitude * np.cos(_TAU * custom), magnitude * np.sin(_TAU * custom)
    if kind == _BOB:
        fresh = drive > 1.0 - (0.15 + 0.35 * custom)
        return 0.0, -magnitude if fresh else magnitude
    norm = np.sqrt(rx * rx + ry * ry) + 1e-9
    if kind == _SPIN:
        sign = -1.0 if custom < 0.5 else 1.0
        return -sign * magnitude * ry / norm, sign * magnitude * rx / norm
    if kind == _REACH:
        dx = (1.0 - custom) * rx / norm
        dy = (1.0 - custom) * ry / norm + custom
        length = np.sqrt(dx * dx + dy * dy) + 1e-9
        return magnitude * dx / length, magnitude * dy / length
    if kind == _SHAKE:
        wave = magnitude * np.cos(2.0 * _TAU * phase)
        angle = 0.25 * _TAU * custom
        return wave * np.cos(angle), wave * np.sin(angle)
    if kind == _SWAY:
        side = -1.0 if custom >= 0.5 else 1.0
        return side * magnitude * np.cos(_TAU * phase), 0.0
    return 0.0, 0.0
