"""The song commands, run through Typer as the main CLI runs them."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import typer
from typer.testing import CliRunner

from sinews.cli.songs import register
from sinews.music import AudioError, load_audio
from sinews.trajectory import Trajectory, TrajectoryError


@pytest.fixture(scope="module")
def app() -> typer.Typer:
    app = typer.Typer()
    register(app)
    return app


def _run(app: typer.Typer, *args: str) -> str:
    result = CliRunner().invoke(app, list(args))
    if result.exception is not None and not isinstance(result.exception, SystemExit):
        raise result.exception
    assert result.exit_code == 0, result.output
    return result.output


def test_demo_then_analyse(
    app: typer.Typer, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    song = tmp_path / "sway.ogg"
    assert "wrote" in _run(app, "songs", "demo", "--name", "sway", "-o", str(song))
    assert load_audio(song).duration > 30
    output = _run(app, "songs", "analyse", str(song))
    assert "96.0 BPM" in output and "beats" in output
    assert "72.0 BPM" in _run(app, "songs", "analyse", str(song), "--bpm", "72")
    assert list((tmp_path / "cache").rglob("*.npz"))


def test_bad_input_raises_sinews_errors(app: typer.Typer, tmp_path: Path) -> None:
    with pytest.raises(AudioError, match="no demo song"):
        _run(app, "songs", "demo", "--name", "nope", "-o", str(tmp_path / "x.wav"))
    with pytest.raises(AudioError, match="no such file"):
        _run(app, "songs", "analyse", str(tmp_path / "missing.mp3"))
    result = CliRunner().invoke(app, ["songs", "analyse", "x.wav", "--bpm", "0"])
    assert result.exit_code == 2  # out of range: a usage error


def _swinging(fps: float, beats: np.ndarray | None) -> Trajectory:
    t = np.arange(int(6 * fps)) / fps
    x = np.cos(np.pi * (t - 0.25) / 0.5)
    positions = np.stack([np.stack([x, np.zeros_like(x)], axis=1)] * 3, axis=1)
    positions[:, :, 1] += np.arange(3) * 0.3
    return Trajectory(positions, fps, np.array([[0, 1], [1, 2]]), ("a", "b", "c"), beats=beats)


def test_score(app: typer.Typer, tmp_path: Path) -> None:
    path = _swinging(60.0, np.arange(0.25, 6.0, 0.5)).save(tmp_path / "on_beat.npz")
    assert "beat-align score 1.000" in _run(app, "score", str(path))
    no_beats = _swinging(60.0, None).save(tmp_path / "no_beats.npz")
    with pytest.raises(TrajectoryError, match="--song"):
        _run(app, "score", str(no_beats))
