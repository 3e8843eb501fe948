"""A motion task's scene drawn with a figure: the X on the floor, a limbo post, a target point.

Obstacles that are bodies of the figure's model (a limbo bar) are drawn with
the figure's own geoms; `TaskScene` holds the marks a model does not have:
the X to hop to, the upright that holds a limbo bar, a point to reach, and the
figure's sites that take part (the hand that reaches, a nose that is the
target). Sites move with the figure, so they are read from the frame's poses.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from sinews.render.canvas import Canvas, Color, shade
from sinews.render.errors import RenderError
from sinews.render.view import View

if TYPE_CHECKING:
    from sinews.figures.task import Task

__all__ = ["TaskScene", "draw_scene_back", "draw_scene_front", "scene_of"]

FloatArray = npt.NDArray[np.float64]

_CROSS: Color = (200, 40, 40)
_POST: Color = (150, 140, 128)
_TARGET: Color = (200, 40, 40)
_TRACKED: Color = (30, 110, 200)


@dataclass(frozen=True)
class TaskScene:
    """The marks a task adds to a figure's picture (world metres, x-z plane).

    Attributes:
        cross: x of an X on the floor (where a hop must end), or None.
        posts: (x, top) of uprights from the floor to ``top`` (a limbo bar's
            centre; the bar is a geom of the model, seen end on).
        target: (x, z) a fixed point to reach, or None.
        target_site: a site of the figure that is the (moving) target, or None.
        tracked_site: the figure's site that must reach the target, or None.
    """

    cross: float | None = None
    posts: tuple[tuple[float, float], ...] = ()
    target: tuple[float, float] | None = None
    target_site: str | None = None
    tracked_site: str | None = None

    def sites(self) -> tuple[str, ...]:
        """The figure's sites the scene marks."""
        return tuple(s for s in (self.target_site, self.tracked_site) if s is not None)

    def points(self) -> FloatArray:
        """(n, 2) the fixed points the picture must show (the floor under the X and post)."""
        points = []
        if self.cross is not None:
            points.append((self.cross, 0.0))
        for x, top in self.posts:
            points += [(x, 0.0), (x, top)]
        if self.target is not None:
            points.append(self.target)
        return np.array(points, dtype=np.float64).reshape(-1, 2)

    def check_sites(self, available: tuple[str, ...]) -> None:
        """`RenderError` if the scene marks a site the figure does not track."""
        missing = [s for s in self.sites() if s not in available]
        if missing:
            raise RenderError(f"the figure has no tracked site {missing[0]!r}")


def draw_scene_back(canvas: Canvas, scene: TaskScene, view: View, text_px: float) -> None:
    """The marks behind the figure: the limbo posts, the X on the floor."""
    for x, top in scene.posts:
        base = view.to_px((x, 0.0))
        head = view.to_px((x, top))
        canvas.line((base[0], base[1]), (head[0], head[1]), _POST, max(2.0, 0.01 * view.scale))
    if scene.cross is not None:
        center = view.to_px((scene.cross, 0.0))
        half = 0.6 * text_px
        cx, cy = float(center[0]), float(center[1]) + 0.5 * half
        for sign in (-1.0, 1.0):
            canvas.line((cx - half, cy - sign * 0.5 * half), (cx + half, cy + sign * 0.5 * half),
                        _CROSS, 3.0)  # fmt: skip


def draw_scene_front(
    canvas: Canvas, scene: TaskScene, view: View, sites: dict[str, FloatArray], text_px: float
) -> None:
    """The marks over the figure: the target (a ring with a cross), the tracked site (a dot).

    Args:
        canvas: where to draw.
        scene: the marks.
        view: the frame's camera.
        sites: site name → its (2,) position in this frame.
        text_px: the painter's text size (marks scale with it).
    """
    radius = 0.5 * text_px
    goal = scene.target if scene.target_site is None else tuple(sites[scene.target_site])
    if goal is not None:
        x, y = (float(v) for v in view.to_px(goal))
        canvas.circle((x, y), radius, None, _TARGET, 2.0)
        canvas.line((x - 1.6 * radius, y), (x + 1.6 * radius, y), _TARGET, 1.0)
        canvas.line((x, y - 1.6 * radius), (x, y + 1.6 * radius), _TARGET, 1.0)
    if scene.tracked_site is not None:
        x, y = (float(v) for v in view.to_px(sites[scene.tracked_site]))
        canvas.circle((x, y), 0.45 * radius, _TRACKED, shade(_TRACKED, 0.6), 1.0)


def scene_of(task: Task) -> TaskScene:
    """The marks a task's picture needs, read from its goal and its touch bodies.

    A goal of the root along the floor (``root_x``, and its height) is an X there;
    a goal at a fixed point is that point; a goal that is a site (the nose) marks
    the site. The site that must reach it is marked too, and every touch body (a
    limbo bar) gets a post from the floor.
    """
    goal, figure = task.goal, task.figure

    def site(column: str) -> str | None:
        name = column.partition("_")[2]
        return name if name in figure.sites else None

    fixed = [t for t in goal.target if not isinstance(t, str)]
    # the root to an X on the floor (x, and its height: `sinews.figures.tasks.on_the_x`)
    on_floor = goal.tracked in (("root_x",), ("root_x", "root_z")) and bool(fixed)
    model = figure.model()
    posts = tuple(
        (float(model.body(b).pos[0]), float(model.body(b).pos[2])) for b in figure.touch_bodies
    )
    return TaskScene(
        cross=float(fixed[0]) if on_floor else None,
        posts=posts,
        target=(float(fixed[0]), float(fixed[1])) if len(fixed) == 2 and not on_floor else None,
        target_site=site(str(goal.target[0])) if not fixed else None,
        tracked_site=site(goal.tracked[0]),
    )
