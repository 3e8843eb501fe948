"""How a frame looks: colours and sizes (`Style`) and the debug overlay (`Overlay`)."""

from __future__ import annotations

import colorsys
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from sinews.render.canvas import Color

__all__ = ["Overlay", "Style", "as_colors", "default_colors"]


@dataclass(frozen=True)
class Style:
    """Colours and sizes of a drawn frame.

    Sizes given as fractions scale with the smaller side of the canvas, so a
    thumbnail and a video frame look alike.

    Attributes:
        background: canvas colour.
        floor: draw the ground line y = 0: True, False, or None to decide from
            the motion (drawn when no node ever sinks clearly below it).
        floor_color: the ground line.
        ground_color: the area under the ground line.
        edge_width: tendon thickness, fraction of the smaller canvas side.
        default_radius: node radius in metres when the trajectory has no radii.
        min_radius_px: no node is drawn smaller than this.
        margin: free border around the fitted motion, fraction of the smaller side.
        text_color: captions and labels.
    """

    background: Color = (250, 248, 243)
    floor: bool | None = None
    floor_color: Color = (120, 114, 104)
    ground_color: Color = (232, 228, 219)
    edge_width: float = 0.005
    default_radius: float = 0.04
    min_radius_px: float = 2.0
    margin: float = 0.06
    text_color: Color = (40, 40, 40)


@dataclass(frozen=True)
class Overlay:
    """The debug overlay drawn "in-game" (the paper's Fig. 2).

    Attributes:
        labels: write each node's name next to it.
        forces: draw each node's force as an arrow (if the trajectory has forces).
        force_scale: arrow pixels per newton; None scales so that a typical
            large force (90th percentile over the whole motion) is
            ``arrow_length`` long.
        arrow_length: that typical arrow, fraction of the smaller canvas side.
        max_arrow: arrows are clipped to this many ``arrow_length``.
        responder_nodes: (R,) node index of each responder (default: the
            trajectory's ``trigger_nodes``); with its triggers (T, R), nodes
            whose responder fires in a frame get a ring.
        arrow_color: force arrows.
        ring_color: rings of firing responders.
    """

    labels: bool = True
    forces: bool = True
    force_scale: float | None = None
    arrow_length: float = 0.12
    max_arrow: float = 2.0
    responder_nodes: Sequence[int] | None = None
    arrow_color: Color = (214, 39, 40)
    ring_color: Color = (255, 170, 0)


def default_colors(n_nodes: int) -> npt.NDArray[np.uint8]:
    """Distinct bright colours for nodes without their own, (N, 3) uint8.

    Hues step by the golden ratio so neighbours differ; the same N always
    gives the same colours.
    """
    hues = (np.arange(n_nodes) * 0.618033988749895 + 0.05) % 1.0
    rgb = [colorsys.hsv_to_rgb(h, 0.65, 0.92) for h in hues]
    return np.round(np.array(rgb, dtype=np.float64).reshape(-1, 3) * 255).astype(np.uint8)


def as_colors(rgb: npt.NDArray[np.floating] | npt.NDArray[np.uint8]) -> list[Color]:
    """(..., 3) channel values as colours (rounded, clipped to 0–255), in row order."""
    clipped = np.clip(np.round(rgb), 0, 255).astype(int).reshape(-1, 3)
    return [(int(r), int(g), int(b)) for r, g, b in clipped]
