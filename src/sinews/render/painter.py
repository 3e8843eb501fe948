"""Drawing one trajectory frame — body, floor, debug overlay, caption — on a `Canvas`."""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from typing import Any

import numpy as np
import numpy.typing as npt

from sinews.render.canvas import Canvas, Color, Point
from sinews.render.errors import RenderError
from sinews.render.style import Overlay, Style, as_colors, default_colors
from sinews.render.view import View, world_bounds
from sinews.trajectory import Trajectory

__all__ = ["FramePainter", "fit_positions", "frame_index", "has_floor", "node_radii"]

_FAR_PX = 1e6  # points further off-canvas than this are not drawn (blown-up runs)
_BLOWN_UP_METRES = 1e3


def _unit_heart(n_points: int = 48) -> npt.NDArray[np.float64]:
    """(n_points, 2) the classic heart curve, x and y (down) in [-1, 1], centred on its box."""
    t = np.linspace(0.0, 2.0 * np.pi, n_points, endpoint=False)
    x = 16.0 * np.sin(t) ** 3
    y = 13.0 * np.cos(t) - 5.0 * np.cos(2 * t) - 2.0 * np.cos(3 * t) - np.cos(4 * t)
    y -= 0.5 * (y.max() + y.min())
    return np.stack([x, -y], axis=1) / 16.0


_HEART = _unit_heart()


def _spike_anchors(traj: Trajectory, spikes: list[int]) -> dict[int, int]:
    """Each spike node's anchor: the other end of its first edge (itself if it has none)."""
    anchors = {}
    for i in spikes:
        (rows,) = np.nonzero((traj.edges == i).any(axis=1))
        anchors[i] = int(traj.edges[rows[0]].sum()) - i if rows.size else i
    return anchors


def _spike(point: Point, anchor: Point, radius: float) -> list[Point]:
    """A triangle on ``point`` pointing away from ``anchor`` (up if they coincide), like an ear."""
    dx, dy = point[0] - anchor[0], point[1] - anchor[1]
    length = float(np.hypot(dx, dy))
    ux, uy = (dx / length, dy / length) if length > 1e-9 else (0.0, -1.0)
    tip = (point[0] + 1.6 * radius * ux, point[1] + 1.6 * radius * uy)
    base = (point[0] - 0.6 * radius * ux, point[1] - 0.6 * radius * uy)
    half = 1.1 * radius
    return [
        tip,
        (base[0] - half * uy, base[1] + half * ux),
        (base[0] + half * uy, base[1] - half * ux),
    ]


def frame_index(traj: Trajectory, frame: int | None) -> int:
    """The frame to draw: ``frame`` (negative counts from the end) or, for None, the middle."""
    n = traj.n_frames
    if n == 0:
        raise RenderError("the trajectory has no frames")
    if frame is None:
        return n // 2
    if not -n <= frame < n:
        raise RenderError(f"frame {frame} is out of range for {n} frames")
    return int(frame) % n


def node_radii(traj: Trajectory, style: Style) -> npt.NDArray[np.float64]:
    """(N,) radii in metres: the trajectory's, or ``style.default_radius`` for every node."""
    if traj.radii is None:
        return np.full(traj.n_nodes, style.default_radius)
    return np.nan_to_num(np.abs(np.asarray(traj.radii, dtype=np.float64)))


def fit_positions(traj: Trajectory) -> npt.NDArray[np.floating]:
    """(T', N, 2) the frames to fit a view to: all, or for a failed run those before it blew up.

    A frame has blown up once a node is non-finite or more than a kilometre out.
    Hidden nodes (``traj.node_visible``) are NaN, so a view ignores them.
    """
    if traj.node_visible is not None:
        shown = np.where(traj.node_visible[..., None], traj.positions, np.nan)
        traj = dataclasses.replace(traj, positions=shown, node_visible=None)
    if not traj.failed:
        return traj.positions
    sane = (np.abs(traj.positions) <= _BLOWN_UP_METRES).all(axis=(1, 2))  # False for NaN too
    first_bad = int(np.argmin(sane)) if not sane.all() else traj.n_frames
    return traj.positions[: max(first_bad, 1)]


def has_floor(traj: Trajectory, style: Style) -> bool:
    """Whether to draw the ground line y = 0.

    ``style.floor`` if set; otherwise whether the motion stands on the ground:
    no node ever sinks below it by more than 2 cm + 5 % of the motion's height.
    """
    if style.floor is not None:
        return style.floor
    box = world_bounds(fit_positions(traj), node_radii(traj, style))
    if box is None:
        return False
    return box[1] >= -(0.02 + 0.05 * (box[3] - box[1]))


class FramePainter:
    """Draws frames of one spring-mass trajectory (a `LayeringPainter`); sizes are worked out once.

    Nodes are discs of their radius (at least ``style.min_radius_px``) in
    their colour with a darker rim (or hearts, or spikes pointing away from
    the other end of their first edge, like ears: see ``traj.node_shapes``);
    tendons are thin lines in the darkened mean colour of their two nodes.
    Non-finite nodes (failed runs) are skipped, and so are nodes and edges a
    frame hides (``traj.node_visible``, ``traj.edge_visible``).

    Args:
        traj: the motion to draw.
        view: where the world appears on the canvas.
        style: colours and sizes; None for `Style()`.
        overlay: the debug overlay (labels, force arrows, responder rings), or None.
        caption: text in the top-left corner, formatted per frame with
            ``{frame}`` (index) and ``{time}`` (seconds), e.g. ``"t = {time:.2f} s"``.
    """

    def __init__(
        self,
        traj: Trajectory,
        view: View,
        *,
        style: Style | None = None,
        overlay: Overlay | None = None,
        caption: str | None = None,
    ) -> None:
        self.traj = traj
        self.view = view
        self.style = style or Style()
        self.overlay = overlay
        self.caption = caption
        side = min(view.width, view.height)
        self._side = side
        fill = (
            default_colors(traj.n_nodes) if traj.colors is None else np.asarray(traj.colors)
        ).astype(np.float64)
        edge_fill = 0.5 * (fill[traj.edges[:, 0]] + fill[traj.edges[:, 1]]) * 0.62
        self._rgb = {"node": fill, "rim": fill * 0.55, "edge": edge_fill}
        self._colors = {key: as_colors(rgb) for key, rgb in self._rgb.items()}
        radii = node_radii(traj, self.style)
        self._radius_px = np.maximum(radii * view.scale, self.style.min_radius_px).tolist()
        shapes = traj.node_shapes or ()
        self._hearts = {i for i, shape in enumerate(shapes) if shape == "heart"}
        self._spikes = _spike_anchors(traj, [i for i, s in enumerate(shapes) if s == "spike"])
        self._edge_px = max(1.0, self.style.edge_width * side)
        self._text_px = max(8.0, 0.022 * side)
        self._floor = has_floor(traj, self.style)
        self._force_scale = self._decide_force_scale()
        self._responders = self._check_responders()
        if caption is not None:
            self._caption_text(0)

    @property
    def size(self) -> tuple[int, int]:
        """(width, height) of the view, pixels."""
        return (self.view.width, self.view.height)

    @property
    def n_frames(self) -> int:
        """Frames of the trajectory."""
        return self.traj.n_frames

    @property
    def fps(self) -> float:
        """The trajectory's frame rate."""
        return self.traj.fps

    def _decide_force_scale(self) -> float | None:
        if self.overlay is None or not self.overlay.forces or self.traj.forces is None:
            return None
        if self.overlay.force_scale is not None:
            return self.overlay.force_scale
        magnitude = np.linalg.norm(np.asarray(self.traj.forces, dtype=np.float64), axis=-1)
        magnitude = magnitude[np.isfinite(magnitude) & (magnitude > 0)]
        if magnitude.size == 0:
            return None
        return self.overlay.arrow_length * self._side / float(np.percentile(magnitude, 90))

    def _check_responders(self) -> npt.NDArray[np.int64] | None:
        if self.overlay is None or self.traj.triggers is None:
            return None
        given: npt.ArrayLike | None = self.overlay.responder_nodes
        if given is None:
            given = self.traj.trigger_nodes
        if given is None:
            return None
        nodes = np.asarray(given, dtype=np.int64).reshape(-1)
        n_responders = np.shape(self.traj.triggers)[1]
        if nodes.size != n_responders:
            raise RenderError(
                f"responder_nodes has {nodes.size} entries for {n_responders} responders"
            )
        if nodes.size and (nodes.min() < 0 or nodes.max() >= self.traj.n_nodes):
            raise RenderError("responder_nodes refers to nodes that do not exist")
        return nodes

    def _caption_text(self, frame: int) -> str:
        assert self.caption is not None
        try:
            return self.caption.format(frame=frame, time=frame / self.traj.fps)
        except (KeyError, IndexError, ValueError, AttributeError) as exc:
            raise RenderError(
                f"bad caption {self.caption!r}: use {{frame}} and {{time}} only ({exc})"
            ) from None

    def draw(self, canvas: Canvas, frames: int | np.integer[Any] | Sequence[int]) -> None:
        """Draw one frame, or several as onion skin (earlier ones faded, the last on top).

        The overlay and caption belong to the last frame.

        Args:
            canvas: where to draw; its size should match the view's.
            frames: frame index, or indices oldest first (negative count from the end).

        Raises:
            RenderError: no frames, or an index out of range.
        """
        chosen = [frames] if isinstance(frames, int | np.integer) else list(frames)
        indices = [frame_index(self.traj, int(f)) for f in chosen]
        if not indices:
            raise RenderError("no frames to draw")
        canvas.clear(self.style.background)
        if self._floor:
            self._draw_floor(canvas)
        for age in range(len(indices) - 1, -1, -1):  # oldest first, fainter the older
            fade = 0.5 + 0.4 * age / len(indices) if age else 0.0
            self._draw_body(canvas, indices[-1 - age], fade)
        last = indices[-1]
        if self.overlay is not None:
            self._draw_overlay(canvas, last, self.overlay)
        if self.caption is not None:
            pad = max(4.0, 0.015 * self._side)
            canvas.text(
                (pad, pad),
                self._caption_text(last),
                self.style.text_color,
                size=max(9.0, 0.03 * self._side),
                halo=self.style.background,
            )

    def _draw_floor(self, canvas: Canvas) -> None:
        width, height = self.view.width, self.view.height
        y = self.view.y_px(0.0)
        if y >= height:
            return
        top = max(y, 0.0)
        corners = [(0.0, top), (float(width), top), (float(width), float(height)), (0.0, height)]
        canvas.polygon(corners, self.style.ground_color)
        if y >= 0.0:
            canvas.line((0.0, y), (float(width), y), self.style.floor_color, self._edge_px)

    def _points(self, frame: int) -> tuple[list[Point], list[bool]]:
        """Canvas position of every node in ``frame``, and which ones can be drawn."""
        px = self.view.to_px(self.traj.positions[frame])
        visible = np.isfinite(px).all(axis=1) & (np.abs(px) < _FAR_PX).all(axis=1)
        if self.traj.node_visible is not None:
            visible &= self.traj.node_visible[frame]
        points = [(x, y) for x, y in np.nan_to_num(px).tolist()]
        return points, np.asarray(visible, dtype=bool).tolist()

    def _faded(self, key: str, fade: float) -> list[Color]:
        if fade == 0.0:
            return self._colors[key]
        background = np.asarray(self.style.background, dtype=np.float64)
        return as_colors(self._rgb[key] * (1.0 - fade) + background * fade)

    def _draw_body(self, canvas: Canvas, frame: int, fade: float) -> None:
        points, visible = self._points(frame)
        edge_colors = self._faded("edge", fade)
        edges = self.traj.edges.tolist()
        shown = (
            range(len(edges))
            if self.traj.edge_visible is None
            else np.flatnonzero(self.traj.edge_visible[frame]).tolist()
        )
        for e in shown:
            i, j = edges[e]
            if visible[i] and visible[j]:
                canvas.line(points[i], points[j], edge_colors[e], self._edge_px)
        rim_width = max(0.75, 0.4 * self._edge_px)
        for i, (fill, rim) in enumerate(
            zip(self._faded("node", fade), self._faded("rim", fade), strict=True)
        ):
            if not visible[i]:
                continue
            if i in self._hearts:
                outline = (_HEART * self._radius_px[i] + points[i]).tolist()
                canvas.polygon([(x, y) for x, y in outline], fill, rim, rim_width)
            elif i in self._spikes:
                corners = _spike(points[i], points[self._spikes[i]], self._radius_px[i])
                canvas.polygon(corners, fill, rim, rim_width)
            else:
                canvas.circle(points[i], self._radius_px[i], fill, rim, rim_width)

    def _draw_overlay(self, canvas: Canvas, frame: int, overlay: Overlay) -> None:
        points, visible = self._points(frame)
        if self._responders is not None and self.traj.triggers is not None:
            fired = np.asarray(self.traj.triggers[frame], dtype=bool)
            for i in np.unique(self._responders[fired]).tolist():
                if visible[i]:
                    r = self._radius_px[i]
                    ring = r + max(3.0, 0.35 * r)
                    canvas.circle(points[i], ring, None, overlay.ring_color, 2.0)
        if self._force_scale is not None and self.traj.forces is not None:
            self._draw_forces(canvas, frame, points, visible, overlay)
        if overlay.labels:
            self._draw_labels(canvas, points, visible)

    def _draw_forces(
        self,
        canvas: Canvas,
        frame: int,
        points: list[Point],
        visible: list[bool],
        overlay: Overlay,
    ) -> None:
        assert self._force_scale is not None and self.traj.forces is not None
        vectors = np.asarray(self.traj.forces[frame], dtype=np.float64) * self._force_scale
        vectors[:, 1] *= -1.0  # y up in the world, down on the canvas
        length = np.linalg.norm(vectors, axis=1)
        longest = overlay.max_arrow * overlay.arrow_length * self._side
        shrink = np.minimum(1.0, longest / np.maximum(length, 1e-12))
        vectors *= shrink[:, None]
        draw = np.asarray(visible) & np.isfinite(length) & (length >= 1.5)
        width = max(1.0, 0.8 * self._edge_px)
        for i in np.flatnonzero(draw).tolist():
            x, y = points[i]
            dx, dy = vectors[i].tolist()
            canvas.arrow((x, y), (x + dx, y + dy), overlay.arrow_color, width)

    def _draw_labels(self, canvas: Canvas, points: list[Point], visible: list[bool]) -> None:
        """Names beside their nodes, on the side away from the body's middle."""
        shown = [i for i, ok in enumerate(visible) if ok]
        if not shown:
            return
        center_x = sum(points[i][0] for i in shown) / len(shown)
        for i in shown:
            x, y = points[i]
            gap = self._radius_px[i] + 2.0
            right = x >= center_x
            canvas.text(
                (x + gap if right else x - gap, y),
                self.traj.node_names[i],
                self.style.text_color,
                size=self._text_px,
                anchor="lm" if right else "rm",
                halo=self.style.background,
            )
