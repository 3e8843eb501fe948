"""Golden pictures: one dancer frame and one figure frame drawn exactly as before.

The inputs are saved motions (``golden/*.npz``, made by ``golden/make_golden.py``),
so these tests catch changes in drawing, not in physics. SVGs are compared
byte for byte (they hold no generated ids), PNGs pixel for pixel, and GIFs
and frame streams (what video encoding is fed) by SHA-256.
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Callable, Iterable
from pathlib import Path

import numpy as np
import numpy.typing as npt
import pytest
from PIL import Image

from sinews.render import (
    FigurePainter,
    NetPanel,
    RasterCanvas,
    SvgCanvas,
    TaskScene,
    iter_frames,
    make_painter,
    paint_frames,
    render,
    render_figure,
)
from sinews.trajectory import Trajectory

GOLDEN = Path(__file__).parent / "golden"
HASHES = GOLDEN / "hashes.json"
CAPTION = "t = {time:.2f} s"
FIGURE_SIZE = (320, 240)
SCENE = TaskScene(cross=1.0, posts=((0.5, 0.2),))


def dancer() -> Trajectory:
    """3 s of a random dancer (genome seed 14, wiggle seed 5) on the groove demo."""
    return Trajectory.load(GOLDEN / "dancer.npz")


def snake_replay() -> tuple[Trajectory, NetPanel]:
    """3 s of the snake driven by a random spring net (seed 14), at 20 frames/s."""
    traj = Trajectory.load(GOLDEN / "snake.npz")
    with np.load(GOLDEN / "snake_net.npz") as net:
        panel = NetPanel(positions=net["positions"], masses=net["masses"],
                         springs=net["springs"], outputs=net["outputs"],
                         labels=tuple(net["labels"].tolist()))  # fmt: skip
    return traj, panel


def _snake_painter(*, still: bool = False) -> FigurePainter:
    from sinews.figures import snake
    from sinews.render import FigureGeometry

    traj, panel = snake_replay()
    return FigurePainter(FigureGeometry.of(snake()), traj, size=FIGURE_SIZE, panel=panel,
                         title="snake", scene=SCENE, still=still)  # fmt: skip


def _dancer_file(path: Path) -> None:
    render(dancer(), path, frame=100, size=(320, 360), overlay=True, caption=CAPTION)


def _dancer_onion(path: Path) -> None:
    render(dancer(), path, frame=[60, 80, 100], size=240)


def _snake_strobe(path: Path) -> None:
    from sinews.figures import snake

    traj, panel = snake_replay()
    render_figure(snake(), traj, path, size=FIGURE_SIZE, panel=panel, title="snake",
                  scene=SCENE, strobe=5)  # fmt: skip


def _snake_frame(path: Path) -> None:
    painter = _snake_painter()
    if path.suffix == ".svg":
        vector = SvgCanvas(painter.width, painter.height)
        painter.draw(vector, 40)
        path.write_text(vector.to_string(), encoding="utf-8")
    else:
        raster = RasterCanvas(painter.width, painter.height)
        painter.draw(raster, 40)
        raster.image().save(path, format="PNG")


PICTURES: dict[str, Callable[[Path], None]] = {
    "dancer_frame.svg": _dancer_file,
    "dancer_frame.png": _dancer_file,
    "dancer_onion.svg": _dancer_onion,
    "snake_strobe.svg": _snake_strobe,
    "snake_strobe.png": _snake_strobe,
    "snake_frame.svg": _snake_frame,
    "snake_frame.png": _snake_frame,
}
"""Golden file name → what draws it."""


def _digest(frames: Iterable[npt.NDArray[np.uint8]]) -> str:
    digest = hashlib.sha256()
    for frame in frames:
        digest.update(np.ascontiguousarray(frame).tobytes())
    return digest.hexdigest()


def _dancer_frames() -> str:
    return _digest(iter_frames(make_painter(dancer(), 160, overlay=True), step=4))


def _snake_frames() -> str:
    painter = _snake_painter()
    return _digest(paint_frames(painter.draw, (painter.width, painter.height),
                                painter.n_frames, step=3))  # fmt: skip


def _dancer_gif(folder: Path) -> str:
    path = render(dancer(), folder / "dancer.gif", fps=15, size=160, caption=CAPTION)
    return hashlib.sha256(path.read_bytes()).hexdigest()


def hashes(folder: Path) -> dict[str, str]:
    """SHA-256 of the moving outputs (``folder`` for scratch files)."""
    return {
        "dancer frames": _dancer_frames(),
        "snake frames": _snake_frames(),
        "dancer.gif": _dancer_gif(folder),
    }


def write_pictures(folder: Path) -> None:
    """Write every golden picture and the hashes to ``folder``."""
    for name, draw in PICTURES.items():
        draw(folder / name)
    found = hashes(folder)
    (folder / "dancer.gif").unlink()
    HASHES.write_text(json.dumps(found, indent=1) + "\n", encoding="utf-8")


def _pixels(path: Path) -> npt.NDArray[np.uint8]:
    with Image.open(path) as image:
        return np.asarray(image.convert("RGB"))


@pytest.mark.parametrize("name", sorted(PICTURES))
def test_pictures_match_the_golden_files(name: str, tmp_path: Path) -> None:
    if name.startswith("snake"):
        pytest.importorskip("mujoco")
    drawn = tmp_path / name
    PICTURES[name](drawn)
    if drawn.suffix == ".svg":
        assert drawn.read_bytes() == (GOLDEN / name).read_bytes()
    else:
        np.testing.assert_array_equal(_pixels(drawn), _pixels(GOLDEN / name))


def test_moving_outputs_match_the_golden_hashes(tmp_path: Path) -> None:
    pytest.importorskip("mujoco")
    assert hashes(tmp_path) == json.loads(HASHES.read_text(encoding="utf-8"))
