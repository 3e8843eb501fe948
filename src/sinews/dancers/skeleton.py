"""The tensegrity humanoid's graph (seed 000, Fig. 1): named nodes and their springs.

A spine (neck, chest, belly, pelvis) is cross-braced to the shoulders and hips
so the torso is a sturdy, flexible tensegrity; limbs hang from it; braces
across the elbows, knees, shoulders and hips give the joints some stiffness.
"""

from __future__ import annotations

from enum import Enum

__all__ = ["EDGES", "EDGE_NAMES", "NODES", "EdgeKind", "edge_kind"]

NODES: tuple[str, ...] = (
    "head", "neck", "chest", "belly", "pelvis",
    "l_shoulder", "r_shoulder", "l_elbow", "r_elbow", "l_hand", "r_hand",
    "l_hip", "r_hip", "l_knee", "r_knee", "l_foot", "r_foot",
)  # fmt: skip
"""Node names; ``l_`` is the dancer's left, drawn at negative x."""


class EdgeKind(Enum):
    """What a spring does in the body; sets its base stiffness."""

    BONE = "bone"
    TORSO = "torso"
    BRACE = "brace"


def _sides(pattern: str) -> list[str]:
    return [pattern.format(s=s) for s in ("l", "r")]


_BONES = [
    "head-neck", "neck-chest", "chest-belly", "belly-pelvis",
    *_sides("neck-{s}_shoulder"), *_sides("{s}_shoulder-{s}_elbow"),
    *_sides("{s}_elbow-{s}_hand"), *_sides("pelvis-{s}_hip"),
    *_sides("{s}_hip-{s}_knee"), *_sides("{s}_knee-{s}_foot"),
]  # fmt: skip
_TORSO = [
    *_sides("{s}_shoulder-chest"), "l_shoulder-r_shoulder", *_sides("{s}_shoulder-belly"),
    *_sides("{s}_hip-belly"), *_sides("{s}_hip-chest"), "l_hip-r_hip",
    *_sides("{s}_shoulder-{s}_hip"), "l_shoulder-r_hip", "r_shoulder-l_hip",
    *_sides("head-{s}_shoulder"), "head-chest",
]  # fmt: skip
_BRACES = [
    *_sides("chest-{s}_elbow"), *_sides("{s}_shoulder-{s}_hand"),
    *_sides("pelvis-{s}_knee"), *_sides("{s}_hip-{s}_foot"),
]  # fmt: skip

EDGE_NAMES: tuple[str, ...] = tuple(_BONES + _TORSO + _BRACES)
"""Edge names ``"a-b"`` in a fixed order (the genome's edge genes follow it)."""

EDGES: tuple[tuple[int, int], ...] = tuple(
    (NODES.index(a), NODES.index(b)) for a, b in (name.split("-") for name in EDGE_NAMES)
)
"""Node index pairs of `EDGE_NAMES`."""

_KINDS = {name: EdgeKind.BONE for name in _BONES} | {name: EdgeKind.TORSO for name in _TORSO}


def edge_kind(name: str) -> EdgeKind:
    """The kind of the edge called ``name``."""
    return _KINDS.get(name, EdgeKind.BRACE)
