"""Files: PNG, SVG, GIF, MP4 with sound, and `render`'s dispatch and errors."""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from pathlib import Path

import imageio_ffmpeg
import numpy as np
import pytest
from PIL import Image, ImageSequence

from render_helpers import decode_audio, make_dancer, probe, write_sine_wav
from sinews.render import (
    RenderError,
    iter_frames,
    make_painter,
    render,
    save_gif,
    save_mp4,
    save_png,
    save_svg,
)
from sinews.trajectory import Trajectory


def test_png_is_a_picture_of_the_dancer(dancer: Trajectory, tmp_path: Path) -> None:
    path = save_png(dancer, tmp_path / "d.png", size=(300, 200), caption="t = {time:.2f} s")
    with Image.open(path) as im:
        assert im.size == (300, 200) and im.mode == "RGB"
        rgb = np.asarray(im)
    assert len(np.unique(rgb.reshape(-1, 3), axis=0)) > 50
    assert list(tmp_path.iterdir()) == [path]  # no temporary file left behind


def test_overlay_png_differs_from_plain(dancer: Trajectory, tmp_path: Path) -> None:
    plain = np.asarray(Image.open(save_png(dancer, tmp_path / "a.png", frame=3)))
    debug = np.asarray(Image.open(save_png(dancer, tmp_path / "b.png", frame=3, overlay=True)))
    assert (plain != debug).any(axis=2).sum() > 500


def test_svg_parses_and_holds_the_body(dancer: Trajectory, tmp_path: Path) -> None:
    path = save_svg(dancer, tmp_path / "d.svg", overlay=True)
    root = ET.parse(path).getroot()
    tags = [el.tag.split("}")[1] for el in root]
    assert tags.count("circle") == dancer.n_nodes
    assert tags.count("line") >= len(dancer.edges)
    texts = {el.text for el in root if el.tag.endswith("text")}
    assert {"head", "l_foot"} <= texts


def gif_durations(path: Path) -> list[int]:
    """Milliseconds each image of a GIF is shown."""
    with Image.open(path) as im:
        assert im.info["loop"] == 0
        return [int(frame.info["duration"]) for frame in ImageSequence.Iterator(im)]


@pytest.mark.parametrize(("fps", "n_frames", "expected"), [(30.0, 30, 30), (60.0, 30, 15)])
def test_gif_has_one_image_per_kept_frame(
    tmp_path: Path, fps: float, n_frames: int, expected: int
) -> None:
    durations = gif_durations(save_gif(make_dancer(n_frames, fps), tmp_path / "d.gif", size=96))
    assert len(durations) == expected
    assert sum(durations) == pytest.approx(1000 * n_frames / fps, abs=10)


def test_gif_frame_rate_can_be_lowered(dancer: Trajectory, tmp_path: Path) -> None:
    assert len(gif_durations(save_gif(dancer, tmp_path / "d.gif", size=64, fps=10))) == 10


def test_mp4_has_an_h264_stream_of_every_frame(dancer: Trajectory, tmp_path: Path) -> None:
    path = save_mp4(dancer, tmp_path / "d.mp4", size=(101, 75))
    info = probe(path)
    assert re.search(r"Video: h264.*yuv420p.*102x76", info)
    assert "Audio:" not in info
    frames, _ = imageio_ffmpeg.count_frames_and_secs(str(path))
    assert frames == dancer.n_frames


@pytest.mark.parametrize("offset", [0.0, 0.25, -0.25])
def test_mp4_carries_the_sound(dancer: Trajectory, tmp_path: Path, offset: float) -> None:
    wav = write_sine_wav(tmp_path / "tone.wav", seconds=2.0)
    path = save_mp4(dancer, tmp_path / "d.mp4", size=64, audio=wav, audio_offset=offset)
    info = probe(path)
    assert "Video: h264" in info and "Audio: aac" in info
    _, seconds = imageio_ffmpeg.count_frames_and_secs(str(path))
    assert seconds == pytest.approx(dancer.duration, abs=0.1)  # -shortest: the picture's length


@pytest.mark.parametrize(
    ("offset", "tone_at"), [(0.0, 0.5), (0.5, 0.0), (0.25, 0.25), (-0.25, 0.75)]
)
def test_audio_offset_is_the_song_time_of_frame_zero(
    tmp_path: Path, offset: float, tone_at: float
) -> None:
    wav = write_sine_wav(tmp_path / "late.wav", seconds=3.0, start=0.5)
    path = save_mp4(make_dancer(45), tmp_path / "d.mp4", size=32, audio=wav, audio_offset=offset)
    sound = np.abs(decode_audio(path, rate=8000))
    loud = np.flatnonzero(sound > 0.05)
    assert loud[0] / 8000 == pytest.approx(tone_at, abs=0.03)


def test_mp4_sound_problems_are_render_errors(dancer: Trajectory, tmp_path: Path) -> None:
    with pytest.raises(RenderError, match="audio file not found"):
        save_mp4(dancer, tmp_path / "d.mp4", audio=tmp_path / "missing.wav")
    junk = tmp_path / "junk.wav"
    junk.write_text("not a sound file")
    with pytest.raises(RenderError, match=r"ffmpeg failed: .+") as excinfo:
        save_mp4(dancer, tmp_path / "d.mp4", size=64, audio=junk)
    assert "\n" not in str(excinfo.value)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["junk.wav"]


@pytest.mark.parametrize("suffix", [".png", ".svg", ".gif", ".mp4"])
def test_render_dispatches_on_the_suffix(dancer: Trajectory, tmp_path: Path, suffix: str) -> None:
    path = render(dancer, tmp_path / f"d{suffix.upper()}", size=64)
    assert path.stat().st_size > 100


def test_render_rejects_unknown_suffixes_and_options(dancer: Trajectory, tmp_path: Path) -> None:
    with pytest.raises(RenderError, match=r"'\.bmp'"):
        render(dancer, tmp_path / "d.bmp")
    with pytest.raises(RenderError, match="no suffix"):
        render(dancer, tmp_path / "d")
    with pytest.raises(RenderError, match="audio"):
        render(dancer, tmp_path / "d.png", audio="song.wav")


@pytest.mark.parametrize("suffix", [".png", ".svg", ".gif", ".mp4"])
def test_unwritable_paths_are_render_errors(
    dancer: Trajectory, tmp_path: Path, suffix: str
) -> None:
    (tmp_path / "file").write_text("")
    for parent in (tmp_path / "missing", tmp_path / "file"):
        with pytest.raises(RenderError, match="cannot write"):
            render(dancer, parent / f"d{suffix}", size=32)


def test_iter_frames_yields_rgb_pictures(dancer: Trajectory) -> None:
    frames = list(iter_frames(make_painter(dancer, (40, 30)), step=4))
    assert len(frames) == 8
    assert all(f.shape == (30, 40, 3) and f.dtype == np.uint8 for f in frames)
    assert not (frames[0] == frames[3]).all()  # the dancer moves
