"""Drawing a headless scene run: the view follows the scene's camera, the score in a corner.

Each scene has its look (`LOOKS`): a sky for Falling for You, a room with
a wooden floor for the kittens, paper for the scribbles. A camera that moves
is applied by drawing the motion relative to it, so the renderer needs no
notion of a moving view.
"""

from __future__ import annotations

import dataclasses
import os
from pathlib import Path

import numpy as np

from sinews.render import Canvas, FramePainter, Overlay, Style, View, render, write
from sinews.scenes.messages import SceneRun
from sinews.trajectory import Trajectory

__all__ = ["LOOKS", "save_scene"]

LOOKS: dict[str, Style] = {
    "falling-for-you": Style(background=(206, 228, 246), floor=False, text_color=(40, 60, 90)),
    "kittens": Style(
        background=(214, 230, 226), floor=True, floor_color=(150, 104, 62),
        ground_color=(202, 160, 112), edge_width=0.006,
    ),
    "scribbles": Style(background=(252, 251, 246), floor=False, edge_width=0.006),
}  # fmt: skip
"""How each scene looks."""


def _in_view(run: SceneRun) -> tuple[Trajectory, tuple[float, float, float, float]]:
    """The motion as the camera sees it, and the world box the view shows."""
    width, height = run.view_size
    camera = run.camera
    traj = run.trajectory
    if np.ptp(camera, axis=0).max() > 0.0:  # a moving camera: draw relative to it
        traj = dataclasses.replace(traj, positions=traj.positions - camera[:, None, :])
        camera = np.zeros_like(camera)
    x, y = camera[0]
    return traj, (x - 0.5 * width, y - 0.5 * height, x + 0.5 * width, y + 0.5 * height)


def save_scene(
    run: SceneRun,
    path: str | os.PathLike[str],
    *,
    height: int = 360,
    fps: float = 30.0,
    overlay: bool = False,
) -> Path:
    """Write a scene run as a video (.mp4, with the score) or a picture (.png, .gif, .svg).

    Args:
        run: what `Scene.record` returned.
        path: file to write; the suffix picks the format.
        height: pixels; the width follows the scene's view.
        fps: highest frame rate of a video.
        overlay: the debug overlay (node labels, and force arrows if the run
            recorded forces).
    """
    traj, box = _in_view(run)
    width_m, height_m = run.view_size
    size = (2 * round(0.5 * height * width_m / height_m), 2 * round(0.5 * height))
    style = LOOKS[run.scene]
    chosen = Overlay() if overlay else None
    path = Path(path)
    if path.suffix.lower() != ".mp4":
        return render(traj, path, size=size, box=box, style=style, overlay=chosen is not None)
    painter = FramePainter(traj, View.fit(box, size, margin=0.0), style=style, overlay=chosen)
    return write(ScorePainter(painter, run), path, kind=".mp4", fps=fps)


@dataclasses.dataclass(frozen=True)
class ScorePainter:
    """A scene's frames with its score in the top-left corner (a `sinews.render.Painter`)."""

    painter: FramePainter
    run: SceneRun

    @property
    def size(self) -> tuple[int, int]:
        """The painter's size."""
        return self.painter.size

    @property
    def n_frames(self) -> int:
        """The run's frames."""
        return self.painter.n_frames

    @property
    def fps(self) -> float:
        """The run's frame rate."""
        return self.painter.fps

    def draw(self, canvas: Canvas, frame: int) -> None:
        """The scene at ``frame`` and, over it, the score then."""
        self.painter.draw(canvas, frame)
        style, height = self.painter.style, self.painter.view.height
        text = f"{self.run.score_name}: {self.run.score[frame]}"
        canvas.text((0.03 * height, 0.03 * height), text, style.text_color,
                    size=0.05 * height, halo=style.background)  # fmt: skip
