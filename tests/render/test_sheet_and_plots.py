"""Contact sheets and fitness plots."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from render_helpers import make_dancer
from sinews.render import RenderError, Style, contact_sheet, plot_fitness
from sinews.trajectory import Trajectory


def body_height_px(cell: np.ndarray, style: Style) -> int:
    """Rows of a cell (above its floor) that hold anything but background."""
    ink = np.abs(cell.astype(int) - style.background).max(axis=2) > 30
    ink[:, -2:] = False  # the cell border
    rows = np.flatnonzero(ink.any(axis=1))
    return int(rows.max() - rows.min())


def test_sheet_size_and_shared_scale(tmp_path: Path) -> None:
    small, big = make_dancer(scale=0.5), make_dancer(scale=1.0)
    path = contact_sheet(
        [small, big, small], tmp_path / "s.png", cols=2, cell=128, labels=["a", "b", "c"]
    )
    with Image.open(path) as im:
        band = round(0.1 * 128)
        assert im.size == (2 * 128, 2 * (128 + band))
        rgb = np.asarray(im)
    style = Style()
    ground = [np.flatnonzero((rgb[:, col] == style.ground_color).all(axis=1)) for col in (2, 130)]
    assert ground[0].size and ground[0][0] == ground[1][0]  # both stand on one floor line
    above = rgb[: ground[0][0] - 3]
    heights = [body_height_px(above[:, :128], style), body_height_px(above[:, 128:], style)]
    assert heights[1] == pytest.approx(2 * heights[0], rel=0.15)


def test_sheet_without_labels_has_no_band(dancer: Trajectory, tmp_path: Path) -> None:
    path = contact_sheet([dancer] * 5, tmp_path / "s.png", cell=64, frame=-1)
    with Image.open(path) as im:
        assert im.size == (3 * 64, 2 * 64)


def test_sheet_errors(dancer: Trajectory, tmp_path: Path) -> None:
    with pytest.raises(RenderError, match="at least one"):
        contact_sheet([], tmp_path / "s.png")
    with pytest.raises(RenderError, match="labels"):
        contact_sheet([dancer], tmp_path / "s.png", labels=["a", "b"])
    with pytest.raises(RenderError, match=r"'\.gif'"):
        contact_sheet([dancer], tmp_path / "s.gif")
    with pytest.raises(RenderError, match="cannot write"):
        contact_sheet([dancer], tmp_path / "nowhere" / "s.png")


@pytest.mark.parametrize("suffix", [".png", ".svg"])
def test_fitness_plot(tmp_path: Path, suffix: str) -> None:
    generations = np.arange(12)
    series = {
        "best": np.sqrt(generations),
        "mean": np.sqrt(generations) / 2,
        "beat alignment": np.linspace(0, 1, 12),
    }
    series["mean"][3] = np.nan
    path = plot_fitness(generations, series, tmp_path / f"f{suffix}", title="run")
    assert path.stat().st_size > 1000
    if suffix == ".png":
        with Image.open(path) as im:
            assert np.asarray(im.convert("L")).std() > 5


def test_fitness_plot_errors(tmp_path: Path) -> None:
    with pytest.raises(RenderError, match="shape"):
        plot_fitness([0, 1, 2], {"best": [1.0, 2.0]}, tmp_path / "f.png")
    with pytest.raises(RenderError, match="at least one"):
        plot_fitness([0, 1, 2], {}, tmp_path / "f.png")
    with pytest.raises(RenderError, match=r"'\.gif'"):
        plot_fitness([0], {"best": [1.0]}, tmp_path / "f.gif")
