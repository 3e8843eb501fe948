"""Drawing replayed individuals of any run kind: one to a file, or several in sequence.

What is drawn follows from what a replay carries, not from the run's kind: a
replay with an articulated figure is drawn as that figure (with its
controller's panel and its task's marks; a 3D figure by MuJoCo's own renderer,
`sinews.render.mujoco_view`); one without is drawn from its nodes
(a spring-mass dancer, with its song as sound in an MP4).
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path
from typing import Any, Protocol

from sinews.errors import SinewsError
from sinews.trajectory import Trajectory

__all__ = ["Drawable", "draw_replays"]


class Drawable(Protocol):
    """What drawing needs of a replay (`sinews.experiments.kinds.Replay` has it)."""

    @property
    def trajectory(self) -> Trajectory: ...

    @property
    def title(self) -> str: ...

    @property
    def audio(self) -> Path | None: ...

    @property
    def figure(self) -> Any: ...

    @property
    def panel(self) -> Any: ...

    @property
    def scene(self) -> Any: ...


def draw_replays(
    replays: Sequence[Drawable],
    path: str | os.PathLike[str],
    *,
    size: int = 480,
    overlay: bool = False,
) -> Path:
    """Draw one replay to ``path`` (by its suffix), or several one after another (an .mp4).

    Args:
        replays: what to draw; several must all be figures.
        path: the file to write.
        size: picture width in pixels (figures are 3/4 as high).
        overlay: node labels and force arrows (replays with recorded forces).
    """
    from sinews.render import (
        FigureGeometry,
        FigurePainter,
        render,
        render_figure,
        render_figure_sequence,
    )

    if not replays:
        raise SinewsError("nothing to draw")
    first = replays[0]
    if first.figure is None:
        if len(replays) > 1:
            raise SinewsError("one dancer at a time: a sequence of generations is for figures")
        sound = {"audio": first.audio} if first.audio and _suffix(path) == ".mp4" else {}
        return render(first.trajectory, path, overlay=overlay, size=size, **sound)
    if overlay:
        raise SinewsError("the debug overlay is for spring-mass bodies, not figures")
    audio = first.audio if _suffix(path) == ".mp4" and len(replays) == 1 else None
    if getattr(first.figure, "root", "planar") == "free":  # 3D: MuJoCo's own renderer
        from sinews.render.mujoco_view import render_recordings_3d

        recordings = [r.trajectory.qpos for r in replays if r.trajectory.qpos is not None]
        return render_recordings_3d(first.figure.model(), recordings, path,
                                    fps=first.trajectory.fps, width=size, audio=audio)  # fmt: skip
    pixels = (size, 3 * size // 4)
    geometry = FigureGeometry.of(first.figure)
    if len(replays) == 1:
        return render_figure(geometry, first.trajectory, path, size=pixels, panel=first.panel,
                             title=first.title, scene=first.scene, audio=audio)  # fmt: skip
    painters = [
        FigurePainter(
            geometry, r.trajectory, size=pixels, panel=r.panel, title=r.title, scene=r.scene
        )
        for r in replays
    ]
    return render_figure_sequence(painters, path)


def _suffix(path: str | os.PathLike[str]) -> str:
    return Path(path).suffix.lower()
