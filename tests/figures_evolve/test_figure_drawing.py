"""Drawing figures from their model and qpos: geometry, camera, pictures, videos, the net panel."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from PIL import Image

pytest.importorskip("mujoco")

from sinews.control import HoldPose
from sinews.figures import Figure, luxo, rollout, snake
from sinews.render import (
    FigureGeometry,
    FigurePainter,
    NetPanel,
    Painter,
    RasterCanvas,
    RenderError,
    SvgCanvas,
    render_figure,
    render_figure_sequence,
)
from sinews.trajectory import Trajectory


def resting(figure: Figure, seconds: float = 0.5) -> Trajectory:
    result = rollout(figure, HoldPose(figure.neutral), 1, seconds, record=True, record_hz=20)
    return result.trajectory(0)


def sliding(figure: Figure, metres: float, frames: int = 40) -> Trajectory:
    """The figure at rest carried along x by ``metres`` (a made-up motion)."""
    qpos = np.tile(figure.model().qpos0, (frames, 1))
    qpos[:, 0] = np.linspace(0.0, metres, frames)
    positions = np.zeros((frames, len(figure.body_names), 2))
    return Trajectory(positions=positions, fps=20.0, edges=figure.edges,
                      node_names=figure.body_names, qpos=qpos)  # fmt: skip


def panel(frames: int) -> NetPanel:
    t = np.linspace(0.0, 2.0, frames)[:, None]
    return NetPanel(positions=np.sin(t * [1.0, 2.0, 3.0]), masses=np.array([0.5, 2.0, 9.0]),
                    springs=np.array([[0, 10, 0], [10, 0, 90], [0, 90, 0]], dtype=float),
                    outputs=np.array([0, 2, 2]), labels=("a", "b", "c"))  # fmt: skip


def test_the_geometry_is_read_from_the_model() -> None:
    lamp = FigureGeometry.of(luxo())
    assert lamp.kinds.tolist() == [6, 3, 3, 3]  # box base, capsule arms and head
    assert lamp.body.tolist() == [0, 1, 2, 3] and lamp.joint_bodies.tolist() == [1, 2, 3]
    np.testing.assert_allclose(lamp.half[0], [0.1, 0.02, 0.0])  # half length and height
    traj = resting(luxo())
    assert traj.qpos is not None and traj.body_pos is not None
    poses = lamp.poses(traj.qpos)
    np.testing.assert_allclose(poses.centers[:, 0], traj.body_pos[:, 0, [0, 2]], atol=1e-6)
    boxes = lamp.extents(poses)
    assert boxes[0, 1] == pytest.approx(0.0, abs=2e-3)  # resting on the floor
    assert 0.3 < boxes[0, 3] < 0.6  # about as tall as a desk lamp


def test_the_camera_follows_a_figure_that_travels_far() -> None:
    geometry = FigureGeometry.of(snake())
    near, far = sliding(snake(), 0.5), sliding(snake(), 8.0)
    fixed = FigurePainter(geometry, near, size=(160, 120))
    assert isinstance(fixed, Painter) and (fixed.size, fixed.fps) == ((160, 120), near.fps)
    assert len({v.left for v in fixed.views}) == 1
    follow = FigurePainter(geometry, far, size=(160, 120))
    lefts = np.array([v.left for v in follow.views])
    assert lefts[-1] - lefts[0] > 5.0 and (np.diff(lefts) >= -1e-9).all()
    still = FigurePainter(geometry, far, size=(160, 120), still=True)
    assert len({v.left for v in still.views}) == 1


def test_pictures_and_videos(tmp_path: Path) -> None:
    figure = snake()
    traj = sliding(figure, 1.0, frames=12)
    geometry = FigureGeometry.of(figure)
    picture = render_figure(geometry, traj, tmp_path / "s.png", size=(200, 150),
                            panel=panel(12), title="snake", strobe=4)  # fmt: skip
    image = np.asarray(Image.open(picture).convert("RGB"))
    assert image.shape == (150, 200, 3)
    assert (np.abs(image.astype(int) - [250, 248, 243]).sum(axis=2) > 60).mean() > 0.05
    svg = render_figure(figure, traj, tmp_path / "s.svg", size=(200, 150))
    assert "<line" in Path(svg).read_text() and "<polygon" in Path(svg).read_text()
    painters = [FigurePainter(geometry, traj, size=(96, 72), panel=panel(12)),
                FigurePainter(geometry, sliding(figure, -1.0, 12), size=(96, 72))]  # fmt: skip
    video = render_figure_sequence(painters, tmp_path / "two.mp4")
    assert Path(video).stat().st_size > 1000


def test_frames_differ_as_the_figure_moves() -> None:
    geometry = FigureGeometry.of(luxo())
    painter = FigurePainter(geometry, sliding(luxo(), 0.3, 10), size=(120, 90), panel=panel(10))
    canvas = RasterCanvas(120, 90)
    painter.draw(canvas, 0)
    first = canvas.to_array().copy()
    painter.draw(canvas, 9)
    assert (first != canvas.to_array()).any()
    vector = SvgCanvas(120, 90)
    painter.draw(vector, [0, 5, 9])
    assert vector.to_string().count("<circle") >= 3  # the net's masses


def test_misuse_is_reported() -> None:
    figure = snake()
    geometry = FigureGeometry.of(figure)
    traj = sliding(figure, 1.0, frames=12)
    with pytest.raises(RenderError, match="frames"):
        FigurePainter(geometry, traj, panel=panel(5))
    with pytest.raises(RenderError, match="qpos"):
        FigurePainter(geometry, Trajectory(np.zeros((3, 3, 2)), 10.0, figure.edges,
                                           figure.body_names))  # fmt: skip
    with pytest.raises(RenderError, match="outputs"):
        NetPanel(np.zeros((3, 2)), np.ones(2), np.zeros((2, 2)), np.array([0, 5]), ("a", "b"))
    with pytest.raises(RenderError, match="cannot write"):
        render_figure(figure, traj, "x.gif")
