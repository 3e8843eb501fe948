"""The one writer and the painters that combine painters."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import imageio_ffmpeg
import numpy as np
import pytest
from PIL import Image, ImageSequence
from render_helpers import probe, write_sine_wav

from sinews.render import (
    Canvas,
    Clips,
    Every,
    Layered,
    Painter,
    RasterCanvas,
    RenderError,
    make_painter,
    reporting_progress,
    write,
)
from sinews.render.painting import frame_step
from sinews.trajectory import Trajectory


@dataclass(frozen=True)
class Dot:
    """A dot moving right a pixel a frame (back every 24 frames); it records what it drew."""

    n_frames: int = 10
    fps: float = 10.0
    size: tuple[int, int] = (32, 24)
    drawn: list[object] | None = None

    def draw(self, canvas: Canvas, frame: int | Sequence[int]) -> None:
        if self.drawn is not None:
            self.drawn.append(frame)
        canvas.clear((255, 255, 255))
        for f in [frame] if isinstance(frame, int) else frame:
            canvas.circle((4.0 + f % 24, 12.0), 3.0, (200, 0, 0))


def test_dancers_figures_and_combinations_are_painters(dancer: Trajectory) -> None:
    painter = make_painter(dancer, (40, 30))
    assert isinstance(painter, Painter)
    assert (painter.size, painter.n_frames, painter.fps) == ((40, 30), 30, dancer.fps)
    for combined in (Layered(painter, (0, 5)), Every(painter, 4), Clips((painter, painter))):
        assert isinstance(combined, Painter) and combined.size == (40, 30)


def test_every_keeps_real_time_and_clips_play_in_turn() -> None:
    drawn: list[object] = []
    every = Every(Dot(drawn=drawn), 3)
    assert (every.n_frames, every.fps) == (4, 10.0 / 3)
    clips = Clips((every, Every(Dot(n_frames=5, drawn=drawn), 3)))
    assert clips.n_frames == 6
    raster = RasterCanvas(32, 24)
    for frame in range(clips.n_frames):
        clips.draw(raster, frame)
    assert drawn == [0, 3, 6, 9, 0, 3]
    with pytest.raises(RenderError, match="past the last clip"):
        clips.draw(raster, 6)


def test_clips_need_one_size_and_rate() -> None:
    with pytest.raises(RenderError, match="no clips"):
        Clips(())
    with pytest.raises(RenderError, match="same size"):
        Clips((Dot(), Dot(fps=20.0)))
    with pytest.raises(RenderError, match="at least 1"):
        Every(Dot(), 0)


def test_frame_step_keeps_at_most_the_wanted_rate() -> None:
    assert frame_step(60.0, None) == 1
    assert frame_step(60.0, 30.0) == 2
    assert frame_step(60.0, 25.0) == 3
    assert frame_step(60.0, None, cap=30.0) == 2
    assert frame_step(20.0, 100.0) == 1
    with pytest.raises(RenderError, match="fps must be positive"):
        frame_step(60.0, 0.0)


def test_any_painter_becomes_every_format(tmp_path: Path) -> None:
    drawn: list[object] = []
    dot = Dot(drawn=drawn)
    png = write(dot, tmp_path / "d.png", frame=7)
    assert np.asarray(Image.open(png)).shape == (24, 32, 3) and drawn == [7]
    assert "<circle" in write(dot, tmp_path / "d.svg").read_text()
    write(Layered(dot, (2, 5)), tmp_path / "layers.png")
    assert drawn[-1] == [2, 5]
    drawn.clear()
    with reporting_progress(lambda done, total: drawn.append((done, total))):
        gif = write(Dot(n_frames=60, fps=60.0), tmp_path / "d.gif")
    with Image.open(gif) as image:
        durations = [int(f.info["duration"]) for f in ImageSequence.Iterator(image)]
    assert durations == [30, 40, 30] * 10  # at most 30 frames/s, in real time (cs ticks)
    assert drawn[-1] == (30, 30)
    mp4 = write(dot, tmp_path / "d.mp4", fps=5.0)
    assert imageio_ffmpeg.count_frames_and_secs(str(mp4)) == (5, pytest.approx(1.0, abs=0.1))


def test_a_video_plays_a_sound_and_misuse_is_reported(tmp_path: Path) -> None:
    song = write_sine_wav(tmp_path / "tone.wav", seconds=2.0)
    assert "Audio: aac" in probe(write(Dot(), tmp_path / "d.mp4", audio=song))
    with pytest.raises(RenderError, match=r"\.png output does not take audio"):
        write(Dot(), tmp_path / "d.png", audio=song)
    with pytest.raises(RenderError, match="audio file not found"):
        write(Dot(), tmp_path / "e.mp4", audio=tmp_path / "missing.wav")
    with pytest.raises(RenderError, match="out of range"):
        write(Dot(), tmp_path / "e.png", frame=10)
    with pytest.raises(RenderError, match="no frames"):
        write(Dot(n_frames=0), tmp_path / "e.gif")
    with pytest.raises(RenderError, match="even"):
        write(Dot(size=(33, 24)), tmp_path / "e.mp4")
    with pytest.raises(RenderError, match="cannot write"):
        write(Dot(), tmp_path / "e.bmp")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["d.mp4", "tone.wav"]
