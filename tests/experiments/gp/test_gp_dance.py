"""GP dances: a changed song stops a resume, and bad songs are refused in one line (every
figure's dance runs, resumed after SIGKILL, in tests/experiments/test_figure_dance_runs.py)."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest

pytest.importorskip("mujoco")

from dance_helpers import click_song, song_folder
from sinews.cli import main
from sinews.store import RunStore

OPTIONS = ["--controller", "gp", "--task", "dance", "--population", "6", "--generations", "4",
           "--seconds", "1.5", "--seed", "2"]  # fmt: skip


@pytest.fixture(scope="module")
def folder(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Path]:
    """A folder with a 2 s song, and the XDG folders (the analysis cache) inside it."""
    where = tmp_path_factory.mktemp("gp_dance")
    with song_folder(where):
        yield where


@pytest.fixture(scope="module")
def whole(folder: Path) -> Path:
    """A finished two-generation dance of the lamp (every figure's dances run in
    tests/experiments/test_figure_dance_runs.py)."""
    db = folder / "whole.db"
    arguments = ["evolve", "luxo", *OPTIONS, "--generations", "2", "--song",
                 str(folder / "song.wav"), "--db", str(db)]  # fmt: skip
    assert main(arguments) == 0
    return db


def test_a_dance_whose_song_changed_is_not_resumed(
    folder: Path, whole: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    moved = folder / "changed"
    moved.mkdir()
    click_song(moved / "song.wav")
    copy = moved / "runs.db"
    copy.write_bytes(whole.read_bytes())
    with RunStore(copy) as store:
        (info,) = store.runs()
        config = {**info.config, "song_path": str(moved / "song.wav"), "song_hash": "0" * 64}
        store.update_config(info.id, config)
    assert main(["runs", "resume", "1", "--generations", "5", "--db", str(copy)]) == 2
    last = capsys.readouterr().err.strip().splitlines()[-1]  # after the progress line
    assert last.startswith("error: ")
    assert last.endswith("the song has changed since the run started")


@pytest.mark.parametrize(
    ("changes", "message"),
    [
        (["--song", "missing.mp3"], "missing.mp3"),
        (["--song", "text.mp3"], "text.mp3"),
        (["--song", "demo:nothing"], "no demo song"),
        ([], "a dance needs a song"),
        (["--song", "song.wav", "--task", "hop"], "--song is for the dance task"),
        (["--song", "song.wav", "--seconds", "5"], "only 2.0 s long"),
    ],
)
def test_bad_songs_are_one_line(
    folder: Path, changes: list[str], message: str, capsys: pytest.CaptureFixture[str],
    monkeypatch: pytest.MonkeyPatch,
) -> None:  # fmt: skip
    (folder / "text.mp3").write_text("not a song")
    monkeypatch.chdir(folder)
    db = folder / "bad.db"
    assert main(["evolve", "luxo", *OPTIONS, *changes, "--db", str(db)]) == 2
    err = capsys.readouterr().err.strip()
    assert message in err and "\n" not in err
    with RunStore(db) as store:
        assert store.runs() == []
