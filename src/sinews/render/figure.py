"""Drawing articulated figures in 2D from their model and a trajectory ("system plus states").

`FigureGeometry` (in `sinews.render.figure_geometry`) is the system: the
figure's capsules, boxes, spheres, cylinders and ellipsoids read from its
compiled MuJoCo model. A trajectory's ``qpos`` frames are the states; forward
kinematics places each geom in the x-z plane. `FigurePainter` draws a frame
on any `Canvas`: the ground with a metre scale, a start marker where the root
began, an arrow from it to the root's x now labelled with the distance, and,
above, an optional `NetPanel`: a spring net's masses as dots moving on its
axis, the springs as arcs, each driving mass in the colour of the part its
joint moves; and an optional `TaskScene` (in `sinews.render.figure_scene`):
the X to hop to, a limbo post, a point to reach.

The camera shows the whole motion when it is short, or when it stays on the
task's scene; when the figure travels more than three times its own size,
it follows the figure at a fixed scale (see `FigurePainter`).
Still pictures (PNG, SVG) are strobe images: poses at even times, older ones
fainter, with the whole path in view. `sinews.render.figure_media` writes
the files.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

from sinews.render.canvas import Canvas, Color, Point, shade
from sinews.render.errors import RenderError
from sinews.render.figure_geometry import (
    CAPSULE,
    ELLIPSOID,
    SPHERE,
    FigureGeometry,
)
from sinews.render.figure_panel import NetPanel, draw_panel
from sinews.render.figure_scene import TaskScene, draw_scene_back, draw_scene_front
from sinews.render.style import Style, as_colors, default_colors
from sinews.render.view import Size, View, pixels
from sinews.trajectory import Trajectory

__all__ = ["FigureGeometry", "FigurePainter", "NetPanel", "TaskScene"]

FloatArray = npt.NDArray[np.float64]

_START_COLOR: Color = (46, 139, 87)
_DISTANCE_COLOR: Color = (200, 60, 40)
_FOLLOW_AFTER = 3.0  # follow a figure whose path is this many times its size
_PANEL_SHARE = 0.22  # of the canvas height
_GROUND_SHARE = 0.2  # of the figure area, below the ground line


class FigurePainter:
    """Draws frames of one figure's trajectory; views and colours are worked out once.

    A `LayeringPainter`: several frames make a strobe picture.

    Args:
        geometry: the figure's geoms.
        traj: its motion (``qpos`` needed).
        size: canvas pixels, an int for a square or (width, height); rounded up to even.
        panel: the controller's net to draw above the figure, or None.
        title: text in the top-left corner of the figure area.
        style: colours; None for `Style()`.
        still: one view of the whole motion (for strobe pictures) instead of a
            follow camera.
        scene: the task's marks (an X, a limbo post, a target), or None.

    Attributes:
        poses: where every geom is in each frame.
        root_x: (T,) the root's x per frame, m.
        views: (T,) the camera of each frame.
    """

    def __init__(
        self,
        geometry: FigureGeometry,
        traj: Trajectory,
        *,
        size: Size = (480, 360),
        panel: NetPanel | None = None,
        title: str | None = None,
        style: Style | None = None,
        still: bool = False,
        scene: TaskScene | None = None,
    ) -> None:
        if traj.qpos is None:
            raise RenderError("a figure trajectory needs qpos")
        if panel is not None and len(panel.positions) != traj.n_frames:
            raise RenderError(f"the panel has {len(panel.positions)} frames, not {traj.n_frames}")
        if scene is not None:
            scene.check_sites(geometry.figure.sites)
        self.geometry, self.traj, self.panel, self.title = geometry, traj, panel, title
        self.scene = scene
        self.style = style or Style()
        self.width, self.height = pixels(size, even=True)
        self.poses = geometry.poses(traj.qpos)
        self.root_x = np.asarray(traj.qpos, dtype=np.float64)[:, 0]
        self._panel_px = round(_PANEL_SHARE * self.height) if panel is not None else 0
        self.views = self._camera(geometry.extents(self.poses), still)
        colors = default_colors(len(geometry.figure.body_names)).astype(np.float64)
        self._fill = as_colors(colors[geometry.body])
        self._joint_colors = as_colors(colors[geometry.joint_bodies])
        self._text_px = max(9.0, 0.045 * min(self.width, self.height))

    @property
    def size(self) -> tuple[int, int]:
        """(width, height), pixels."""
        return (self.width, self.height)

    @property
    def n_frames(self) -> int:
        """Frames of the trajectory."""
        return self.traj.n_frames

    @property
    def fps(self) -> float:
        """The trajectory's frame rate."""
        return self.traj.fps

    def _camera(self, boxes: FloatArray, still: bool) -> list[View]:
        """One view per frame: fixed on the whole motion, or following the figure.

        The figure's size is the largest side of its own box over the frames. A
        path longer or higher than `_FOLLOW_AFTER` sizes is followed (smoothed
        over half a second) in a window that many sizes wide and at most half
        as high, the ground at the bottom unless the figure flies above it;
        a path that stays within a size of the stage (from the start to the
        scene's farthest mark) is not.
        """
        usable = self.height - self._panel_px - _GROUND_SHARE * (self.height - self._panel_px)
        ground_row = self.height - _GROUND_SHARE * (self.height - self._panel_px)
        size = max(float((boxes[:, 2:] - boxes[:, :2]).max()), 0.05)
        pad = 0.15 * size
        x_lo = min(float(boxes[:, 0].min()), float(self.root_x[0])) - pad
        x_hi = max(float(boxes[:, 2].max()), float(self.root_x[0])) + pad
        y_low, y_top = min(float(boxes[:, 1].min()), 0.0), float(boxes[:, 3].max()) + pad
        reach = _FOLLOW_AFTER * size
        marks = self.scene.points() if self.scene is not None else np.zeros((0, 2))
        on_stage = False
        if len(marks):  # the stage: from the start to the farthest mark
            stage = np.append(marks[:, 0], self.root_x[0])
            on_stage = x_lo >= stage.min() - size and x_hi <= stage.max() + size
            x_lo, x_hi = min(x_lo, stage.min() - 2 * pad), max(x_hi, stage.max() + 2 * pad)
            y_top = max(y_top, marks[:, 1].max() + pad)
        if still or on_stage or (x_hi - x_lo <= reach and y_top - y_low <= reach):
            scale = min(self.width / (x_hi - x_lo), (usable - 4.0) / (y_top - y_low))
            left = 0.5 * (x_lo + x_hi) - 0.5 * self.width / scale
            view = View(self.width, self.height, scale, left, y_low + ground_row / scale)
            return [view] * self.n_frames
        scale = min(self.width / reach, (usable - 4.0) / min(y_top - y_low, 0.5 * reach))
        seen = (usable - 4.0) / scale  # world height above the ground band
        x_mid = _smooth(0.5 * (boxes[:, 0] + boxes[:, 2]), self.traj.fps)
        y_mid = _smooth(0.5 * (boxes[:, 1] + boxes[:, 3]), self.traj.fps)
        bottom = np.maximum(y_low, y_mid - 0.5 * seen)
        half = 0.5 * self.width / scale
        return [
            View(self.width, self.height, scale, x - half, b + ground_row / scale)
            for x, b in zip(x_mid.tolist(), bottom.tolist(), strict=True)
        ]

    def draw(self, canvas: Canvas, frames: int | Sequence[int]) -> None:
        """Draw one frame, or several as a strobe (earlier ones fainter, the last on top).

        Args:
            canvas: where to draw; its size should be the painter's.
            frames: frame index, or indices oldest first.
        """
        chosen = [frames] if isinstance(frames, int) else list(frames)
        if not chosen or not all(0 <= f < self.n_frames for f in chosen):
            raise RenderError(f"frames must be in [0, {self.n_frames}), got {chosen}")
        last = chosen[-1]
        view = self.views[last]
        canvas.clear(self.style.background)
        self._draw_ground(canvas, view)
        self._draw_start(canvas, view)
        if self.scene is not None:
            draw_scene_back(canvas, self.scene, view, self._text_px)
        for k, frame in enumerate(chosen):  # oldest first, fainter the older
            age = len(chosen) - 1 - k
            fade = 0.0 if age == 0 else 0.45 + 0.45 * age / len(chosen)
            self._draw_body(canvas, view, frame, fade)
        if self.scene is not None:
            names = self.geometry.figure.sites
            sites = dict(zip(names, self.poses.sites[last], strict=True))
            draw_scene_front(canvas, self.scene, view, sites, self._text_px)
        self._draw_markers(canvas, view, last)
        if self.panel is not None:
            draw_panel(
                canvas, self.panel, last, (self.width, self._panel_px),
                joint_colors=self._joint_colors, style=self.style,
            )  # fmt: skip
        if self.title is not None:
            pad = 0.4 * self._text_px
            canvas.text((pad, self._panel_px + pad), self.title, self.style.text_color,
                        size=self._text_px, halo=self.style.background)  # fmt: skip

    def _draw_ground(self, canvas: Canvas, view: View) -> None:
        y = view.y_px(0.0)
        corners = [(0.0, y), (float(self.width), y), (float(self.width), float(self.height)),
                   (0.0, float(self.height))]  # fmt: skip
        canvas.polygon(corners, self.style.ground_color)
        canvas.line((0.0, y), (float(self.width), y), self.style.floor_color, 1.5)
        step = next(s for s in (0.1, 0.2, 0.25, 0.5, 1.0, 2.0, 5.0, 10.0, 1e9)
                    if s * view.scale >= 40)  # fmt: skip
        x0, _, x1, _ = view.box
        for k in range(math.ceil(x0 / step), math.floor(x1 / step) + 1):
            px = view.to_px((k * step, 0.0))[0]
            canvas.line((px, y), (px, y + 5.0), self.style.floor_color, 1.0)
            canvas.text((px, y + 5.0), f"{k * step:g}", shade(self.style.floor_color, 1.1),
                        size=0.7 * self._text_px, anchor="mt")  # fmt: skip

    def _draw_body(self, canvas: Canvas, view: View, frame: int, fade: float) -> None:
        poses, half = self.poses, self.geometry.half
        center, ax, az = poses.centers[frame], poses.ax[frame], poses.az[frame]
        background = np.asarray(self.style.background, dtype=np.float64)
        for k, kind in enumerate(self.geometry.kinds.tolist()):
            fill_rgb = np.asarray(self._fill[k], dtype=np.float64) * (1 - fade) + background * fade
            (fill,) = as_colors(fill_rgb)
            (rim,) = as_colors(fill_rgb * 0.55 * (1 - fade) + background * fade)
            c, sx, sz, r = center[k], ax[k] * half[k, 0], az[k] * half[k, 1], half[k, 2]
            if kind in (CAPSULE, SPHERE):
                ends = view.to_px(np.array([c - sz, c + sz]))
                start, end = (ends[0, 0], ends[0, 1]), (ends[1, 0], ends[1, 1])
                radius = max(r * view.scale, 1.0)
                if kind == SPHERE or np.allclose(start, end):
                    canvas.circle(start, radius, fill, rim, 1.0)
                else:
                    canvas.line(start, end, rim, 2.0 * radius + 2.0)
                    canvas.line(start, end, fill, 2.0 * radius)
            else:
                if kind == ELLIPSOID:
                    angles = np.linspace(0.0, 2.0 * np.pi, 24, endpoint=False)[:, None]
                    outline = c + np.cos(angles) * sx + np.sin(angles) * sz
                else:
                    outline = np.array([c - sx - sz, c + sx - sz, c + sx + sz, c - sx + sz])
                points: list[Point] = [(x, y) for x, y in view.to_px(outline).tolist()]
                canvas.polygon(points, fill, rim, 1.0)

    def _below(self, view: View) -> float:
        """The canvas row of the distance arrow, inside the ground band."""
        ground = view.y_px(0.0)
        return min(ground + 0.45 * _GROUND_SHARE * (self.height - self._panel_px),
                   self.height - 1.2 * self._text_px)  # fmt: skip

    def _draw_start(self, canvas: Canvas, view: View) -> None:
        """A flag where the root started, down to the distance arrow."""
        ground = view.y_px(0.0)
        start = float(view.to_px((self.root_x[0], 0.0))[0])
        flag = ground - 0.12 * (self.height - self._panel_px)
        canvas.line((start, ground), (start, flag), _START_COLOR, 2.0)
        canvas.polygon([(start, flag), (start + 9.0, flag + 3.5), (start, flag + 7.0)],
                       _START_COLOR)  # fmt: skip
        canvas.line((start, ground), (start, self._below(view) + 4.0), _START_COLOR, 1.0)

    def _draw_markers(self, canvas: Canvas, view: View, frame: int) -> None:
        below = self._below(view)
        start = float(view.to_px((self.root_x[0], 0.0))[0])
        now = float(view.to_px((self.root_x[frame], 0.0))[0])
        distance = self.root_x[frame] - self.root_x[0]
        if abs(now - start) >= 2.0:
            canvas.arrow((start, below), (now, below), _DISTANCE_COLOR, 2.0)
        middle = min(
            max(0.5 * (start + now), 3.0 * self._text_px), self.width - 3.0 * self._text_px
        )
        label = f"{abs(distance):.2f} m"
        canvas.text((middle, below + 3.0), label, _DISTANCE_COLOR, size=0.9 * self._text_px,
                    anchor="mt", halo=self.style.ground_color)  # fmt: skip
        canvas.text((self.width - 0.4 * self._text_px, self._panel_px + 0.4 * self._text_px),
                    f"{frame / self.traj.fps:.1f} s", self.style.text_color,
                    size=self._text_px, anchor="rt", halo=self.style.background)  # fmt: skip


def _smooth(values: FloatArray, fps: float) -> FloatArray:
    """A running mean over half a second, edges held."""
    window = max(1, round(fps / 4))
    kernel = np.ones(2 * window + 1) / (2 * window + 1)
    return np.convolve(np.pad(values, window, mode="edge"), kernel, mode="valid")
