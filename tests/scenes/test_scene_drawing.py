"""Drawing scenes: hidden parts stay hidden, balloons are hearts, ears are spikes, videos play."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from sinews.cli import main
from sinews.render import FramePainter, RasterCanvas, Style, View
from sinews.trajectory import Trajectory, TrajectoryError

RED = (220, 30, 50)
BLUE = (30, 60, 220)


def scene_like(shapes: tuple[str, ...] = ("disc", "heart", "spike")) -> Trajectory:
    """Two frames of three nodes; node 2 and edge 1 are hidden in frame 0."""
    positions = np.array([[[-0.5, 0.0], [0.5, 0.0], [0.0, 0.6]]] * 2, dtype=np.float32)
    return Trajectory(
        positions=positions,
        fps=60.0,
        edges=np.array([[0, 1], [1, 2]]),
        node_names=("a", "b", "c"),
        radii=np.array([0.1, 0.25, 0.1], dtype=np.float32),
        colors=np.array([BLUE, RED, BLUE], dtype=np.uint8),
        node_visible=np.array([[True, True, False], [True, True, True]]),
        edge_visible=np.array([[True, False], [True, True]]),
        node_shapes=shapes,
    )


def draw(traj: Trajectory, frame: int) -> tuple[np.ndarray, View]:
    view = View.fit((-1.0, -1.0, 1.0, 1.0), (200, 200), margin=0.0)
    canvas = RasterCanvas(200, 200)
    FramePainter(traj, view, style=Style(floor=False)).draw(canvas, frame)
    return canvas.to_array().astype(int), view


def near(rgb: np.ndarray, color: tuple[int, int, int]) -> np.ndarray:
    return np.abs(rgb - np.array(color)).max(axis=2) < 40


def test_hidden_nodes_and_edges_are_not_drawn() -> None:
    traj = scene_like(("disc", "disc", "disc"))
    hidden, view = draw(traj, 0)
    shown, _ = draw(traj, 1)
    x, y = np.round(view.to_px(traj.positions[0, 2])).astype(int)
    assert near(shown, BLUE)[y - 2 : y + 3, x - 2 : x + 3].all()
    assert not near(hidden, BLUE)[y - 2 : y + 3, x - 2 : x + 3].any()
    assert (shown != hidden).any(axis=2).sum() > 200  # the node and the edge to it


def test_a_heart_is_a_heart_and_an_ear_points_away_from_its_head() -> None:
    rgb, view = draw(scene_like(), 1)
    red = near(rgb, RED)
    cx, cy = np.round(view.to_px(np.array([0.5, 0.0]))).astype(int)
    radius = 0.25 * view.scale
    assert red[cy, cx] and red.sum() > 0.6 * np.pi * radius**2  # a filled shape that big
    top = red[cy - int(0.75 * radius), cx - int(0.45 * radius) : cx + int(0.45 * radius)]
    assert not top[len(top) // 2] and top[0] and top[-1]  # the dip between the two lobes
    tip = cy + int(0.7 * radius)
    assert red[tip, cx] and not red[tip, cx - int(0.55 * radius)]  # narrowing to a point
    ear = near(rgb, BLUE)
    b, c = scene_like().positions[1, 1], scene_like().positions[1, 2]
    away = (c - b) / np.hypot(*(c - b))  # its first edge joins it to b
    for reach, inside in ((1.3, True), (-1.3, False)):
        x, y = np.round(view.to_px(c + reach * 0.1 * away)).astype(int)
        assert ear[y, x] == inside  # a point away from b, nothing behind


def test_visibility_and_shapes_survive_a_file_and_are_checked(tmp_path: Path) -> None:
    traj = scene_like()
    back = Trajectory.load(traj.save(tmp_path / "scene.npz"))
    assert traj.node_visible is not None and traj.edge_visible is not None
    assert back.node_shapes == traj.node_shapes
    assert back.node_visible is not None and np.array_equal(back.node_visible, traj.node_visible)
    assert back.edge_visible is not None and np.array_equal(back.edge_visible, traj.edge_visible)
    with pytest.raises(TrajectoryError, match="unknown node shape 'star'"):
        scene_like(("disc", "star", "disc"))
    with pytest.raises(TrajectoryError, match="edge_visible must have shape"):
        wrong = np.ones((2, 3), dtype=bool)
        Trajectory(traj.positions, 60.0, traj.edges, traj.node_names, edge_visible=wrong)


def test_the_scene_command_plays_draws_and_saves(tmp_path: Path) -> None:
    video, motion = tmp_path / "kittens.mp4", tmp_path / "kittens.npz"
    argv = ["scene", "kittens", "--seconds", "1", "-o", str(video), "--trajectory", str(motion)]
    assert main([*argv, "--debug-overlay", "--height", "120"]) == 0
    assert video.stat().st_size > 1000
    traj = Trajectory.load(motion)
    assert traj.n_frames == 61 and traj.forces is not None and traj.node_visible is not None
    still = tmp_path / "doll.png"
    assert main(["scene", "falling-for-you", "--seconds", "0.2", "-o", str(still)]) == 0
    assert still.stat().st_size > 1000


def test_the_scene_command_names_the_scenes_it_knows(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["scene", "puppies", "-o", "x.mp4"]) == 2
    assert "choose from falling-for-you, kittens, scribbles" in capsys.readouterr().err
