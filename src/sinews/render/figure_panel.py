"""The spring-net panel drawn above a figure: masses as dots moving on the net's axis."""

from __future__ import annotations

import itertools
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from sinews.render.canvas import Canvas, Color, Point, shade
from sinews.render.errors import RenderError
from sinews.render.style import Style

__all__ = ["NetPanel", "draw_panel"]

FloatArray = npt.NDArray[np.float64]

_HIDDEN: Color = (150, 150, 150)
_SPRING: Color = (170, 165, 155)


@dataclass(frozen=True, eq=False)
class NetPanel:
    """A spring net's motion, to draw beside the figure it drives.

    Attributes:
        positions: (T, n) each mass's position on the net's axis, per frame.
        masses: (n,) the point masses.
        springs: (n, n) spring constants (0: no spring).
        outputs: (n_act,) the mass driving each actuated joint.
        labels: (n_act,) the joints' names.
    """

    positions: FloatArray
    masses: FloatArray
    springs: FloatArray
    outputs: npt.NDArray[np.integer]
    labels: Sequence[str]

    def __post_init__(self) -> None:
        positions = np.asarray(self.positions, dtype=np.float64)
        n = np.shape(self.masses)[0] if np.ndim(self.masses) == 1 else -1
        if positions.ndim != 2 or positions.shape[1] != n:
            raise RenderError(f"positions must have shape (T, {n}), got {positions.shape}")
        if np.shape(self.springs) != (n, n):
            raise RenderError(f"springs must have shape ({n}, {n})")
        outputs = np.asarray(self.outputs)
        if outputs.ndim != 1 or len(outputs) != len(self.labels):
            raise RenderError("outputs and labels need one entry per joint")
        if outputs.size and (outputs.min() < 0 or outputs.max() >= n):
            raise RenderError("outputs must be mass indices")

    @property
    def bounds(self) -> tuple[float, float]:
        """The stretch of axis shown: every position of every frame, padded."""
        finite = self.positions[np.isfinite(self.positions)]
        lo, hi = (float(finite.min()), float(finite.max())) if finite.size else (-1.0, 1.0)
        pad = max(0.08 * (hi - lo), 0.5 * max(0.0, 0.3 - (hi - lo)))
        return lo - pad, hi + pad


def draw_panel(
    canvas: Canvas,
    panel: NetPanel,
    frame: int,
    size: tuple[int, int],
    *,
    joint_colors: Sequence[Color],
    style: Style,
) -> None:
    """Draw ``panel`` at ``frame`` in the band ``size`` = (width, height) at the canvas top.

    Springs are arcs above the axis (thicker for stiffer), masses dots (bigger
    for heavier); a mass driving a joint has that joint's colour (``joint_colors``,
    one per actuator) and its name below.
    """
    width, height = size
    canvas.polygon([(0.0, 0.0), (float(width), 0.0), (float(width), float(height)),
                    (0.0, float(height))], shade(style.background, 0.96))  # fmt: skip
    canvas.line((0.0, height - 0.5), (float(width), height - 0.5), shade(style.background, 0.8))
    text_px = max(8.0, 0.16 * height)
    canvas.text((4.0, 3.0), "spring net", style.text_color, size=text_px)
    margin, axis_y = 0.06 * width, 0.55 * height
    lo, hi = panel.bounds
    x = margin + (panel.positions[frame] - lo) / (hi - lo) * (width - 2 * margin)
    canvas.line((margin, axis_y), (width - margin, axis_y), shade(style.background, 0.7), 1.0)
    n = len(panel.masses)
    for i in range(n):
        for j in range(i + 1, n):
            if panel.springs[i, j] > 0:
                _arc(canvas, float(x[i]), float(x[j]), axis_y, 0.4 * height,
                     0.5 + 2.5 * float(panel.springs[i, j]) / 100.0)  # fmt: skip
    drives: dict[int, list[int]] = {}
    for joint, mass in enumerate(np.asarray(panel.outputs).tolist()):
        drives.setdefault(mass, []).append(joint)
    for i in np.argsort(-np.asarray(panel.masses)).tolist():  # light masses on top
        radius = max(2.5, 0.13 * height * float(np.cbrt(panel.masses[i] / 10.0)))
        joints = drives.get(i, [])
        color = joint_colors[joints[0]] if joints else _HIDDEN
        center: Point = (float(x[i]), axis_y)
        canvas.circle(center, radius, color, shade(color, 0.55), 1.0)
        if joints:
            canvas.text((center[0], axis_y + radius + 1.0),
                        ",".join(panel.labels[j] for j in joints), shade(color, 0.6),
                        size=0.85 * text_px, anchor="mt")  # fmt: skip


def _arc(canvas: Canvas, x0: float, x1: float, y: float, most: float, width: float) -> None:
    """A half-ellipse from (x0, y) to (x1, y) bulging up by at most ``most`` pixels."""
    rise = min(most, 0.5 * abs(x1 - x0))
    if rise < 0.5:
        return
    t = np.linspace(0.0, np.pi, 13)
    xs = 0.5 * (x0 + x1) - 0.5 * (x1 - x0) * np.cos(t)
    ys = y - rise * np.sin(t)
    points = list(zip(xs.tolist(), ys.tolist(), strict=True))
    for a, b in itertools.pairwise(points):
        canvas.line(a, b, _SPRING, width)
