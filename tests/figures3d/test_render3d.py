"""Offscreen MuJoCo rendering of 3D runs: frames that show the figure, files, the GL error."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from PIL import Image

pytest.importorskip("mujoco")

from sinews.figures.tasks import make_task
from sinews.render import mujoco_view
from sinews.render.mujoco_view import (
    GLBackendError,
    MujocoView,
    default_camera,
    save_mp4_3d,
    save_png_3d,
    save_strobe_3d,
)


@pytest.fixture(scope="module")
def hop() -> Any:
    task = make_task("luxo3d-hop", target=(1.0, 0.5))
    model = task.figure.model()
    try:
        MujocoView(model, 32, 32).close()
    except GLBackendError as exc:
        pytest.skip(str(exc))
    return model


def _figure_mask(image: np.ndarray) -> np.ndarray:
    """Where the figures' orange or blue is (the floor is grey, the sky pale blue-white)."""
    r, g, b = (image[..., k].astype(int) for k in range(3))
    orange = (r - b > 60) & (g < r - 25)
    blue = (b - r > 60) & (b > 60)
    return orange | blue


def _figure(image: np.ndarray) -> int:
    """Pixels of the figures."""
    return int(_figure_mask(image).sum())


def _red(image: np.ndarray) -> int:
    r, g, b = (image[..., k].astype(int) for k in range(3))
    return int(((r > 120) & (g < 80) & (b < 80)).sum())


def test_a_frame_shows_the_lamp_and_the_x(hop: Any) -> None:
    with MujocoView(hop, 320, 180, camera=default_camera(hop, hop.qpos0)) as view:
        image = view.frame(hop.qpos0)
    assert image.shape == (180, 320, 3) and image.dtype == np.uint8
    assert image.std() > 10  # not blank
    assert _figure(image) > 60  # the lamp is in view
    assert _red(image) > 10  # the target's X too


def test_the_camera_follows_the_figure(hop: Any) -> None:
    moved = hop.qpos0.copy()
    moved[:2] = (1.5, -1.0)  # far from where the camera started
    with MujocoView(hop, 320, 180) as view:
        view.frame(hop.qpos0)
        image = view.frame(moved)  # no lag given: the camera jumps
    assert _figure(image) > 60


@pytest.mark.parametrize("heading", [180.0, 225.0])
def test_a_strobe_shows_the_poses_side_by_side_whichever_way_the_figure_went(
    hop: Any, heading: float, tmp_path: Path
) -> None:
    """Eight poses 0.2 m apart along a line (backwards, backwards and to the right): the
    default camera sees them from the side, so at least five stand apart in the picture
    (from the usual front-right view, 3 and 4 groups)."""
    qpos = np.repeat(hop.qpos0[None], 8, axis=0)
    step = np.radians(heading)
    qpos[:, :2] = np.arange(8)[:, None] * 0.2 * np.array([np.cos(step), np.sin(step)])
    image = np.asarray(Image.open(save_strobe_3d(hop, qpos, tmp_path / "s.png", count=8,
                                                 size=(320, 180))))  # fmt: skip
    columns = np.flatnonzero(_figure_mask(image).any(axis=0))
    assert np.count_nonzero(np.diff(columns) > 1) + 1 >= 5


def test_png_strobe_and_mp4_files(hop: Any, tmp_path: Path) -> None:
    qpos = np.repeat(hop.qpos0[None], 12, axis=0)
    qpos[:, 0] = np.linspace(0.0, 0.6, 12)
    png = save_png_3d(hop, qpos, tmp_path / "last.png", size=(320, 180))
    strobe = save_strobe_3d(hop, qpos, tmp_path / "strobe.png", count=4, size=(320, 180))
    video = save_mp4_3d(hop, qpos, tmp_path / "run.mp4", fps=30, size=(320, 180))
    assert np.asarray(Image.open(png)).shape == (180, 320, 3)
    assert _figure(np.asarray(Image.open(strobe))) > 60
    assert video.stat().st_size > 600
    assert sorted(p.name for p in tmp_path.iterdir()) == ["last.png", "run.mp4", "strobe.png"]


def test_a_missing_gl_back_end_is_one_line_naming_the_package(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.setenv("MUJOCO_GL", "osmesa")
    monkeypatch.setitem(sys.modules, "mujoco.osmesa", None)  # as if libOSMesa could not load
    with pytest.raises(GLBackendError) as info:
        mujoco_view._context_class("osmesa")
    message = str(info.value)
    assert "libosmesa6" in message and "\n" not in message


def test_an_unknown_back_end_is_refused(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("MUJOCO_GL", "vulkan-please")
    with pytest.raises(GLBackendError, match="unknown MUJOCO_GL"):
        mujoco_view._context_class(mujoco_view.gl_backend())
