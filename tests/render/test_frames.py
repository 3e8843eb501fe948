"""One frame loop for every moving output, and the progress it reports."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from sinews.render import Canvas, paint_frames, render, reporting_progress
from sinews.trajectory import Trajectory


def test_paint_frames_draws_every_step_th_frame_and_reports_each() -> None:
    drawn: list[int] = []
    reports: list[tuple[int, int]] = []

    def draw(canvas: Canvas, frame: int) -> None:
        drawn.append(frame)
        canvas.circle((10.0, 10.0), 2.0 + frame, (200, 0, 0))

    with reporting_progress(lambda done, total: reports.append((done, total))):
        pictures = list(paint_frames(draw, (32, 24), 10, step=3))
    assert drawn == [0, 3, 6, 9]
    assert reports == [(1, 4), (2, 4), (3, 4), (4, 4)]
    assert all(p.shape == (24, 32, 3) and p.dtype == np.uint8 for p in pictures)
    assert not np.array_equal(pictures[0], pictures[-1])  # the circle grew


def test_a_gif_reports_its_frames_and_nothing_outside_the_block(tmp_path: Path) -> None:
    positions = np.zeros((12, 2, 2), np.float32)
    positions[:, 1, 0] = np.linspace(0.1, 0.5, 12)
    traj = Trajectory(positions, fps=12.0, edges=np.array([[0, 1]]), node_names=("a", "b"))
    reports: list[tuple[int, int]] = []
    with reporting_progress(lambda done, total: reports.append((done, total))):
        render(traj, tmp_path / "a.gif", size=64)
    assert reports and reports[-1][0] == reports[-1][1] == len(reports)
    seen = len(reports)
    render(traj, tmp_path / "b.gif", size=64)
    assert len(reports) == seen
