"""GP dances through the installed ``sinews``: stored with the song's hash, resumed bit for
bit after SIGKILL, and bad songs refused in one line."""

from __future__ import annotations

import hashlib
import subprocess
from collections.abc import Iterator
from pathlib import Path

import pytest

pytest.importorskip("mujoco")

from dance_helpers import click_song
from gp_helpers import stored
from killed_runs import kill_when, sinews_command, stored_generations
from sinews.cli import main
from sinews.experiments.run_files import fitness_plot
from sinews.store import RunStore

OPTIONS = ["--controller", "gp", "--task", "dance", "--population", "6", "--generations", "4",
           "--seconds", "1.5", "--seed", "2"]  # fmt: skip


@pytest.fixture(scope="module")
def folder(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Path]:
    """A folder with a 2 s song, and the XDG folders (the analysis cache) inside it."""
    where = tmp_path_factory.mktemp("gp_dance")
    click_song(where / "song.wav")
    with pytest.MonkeyPatch.context() as patch:
        for name in ("XDG_CACHE_HOME", "XDG_DATA_HOME"):
            patch.setenv(name, str(where / name.lower()))
        yield where


def arguments(folder: Path, db: str) -> list[str]:
    return ["evolve", "luxo", *OPTIONS, "--song", str(folder / "song.wav"), "--db",
            str(folder / db)]  # fmt: skip


@pytest.fixture(scope="module")
def whole(folder: Path) -> Path:
    done = subprocess.run([*sinews_command(), *arguments(folder, "whole.db")],
                          capture_output=True, text=True, check=False)  # fmt: skip
    assert done.returncode == 0, done.stderr[-2000:]
    return folder / "whole.db"


def test_a_dance_is_stored_with_its_song_and_rated_by_the_beat(folder: Path, whole: Path) -> None:
    status, individuals, checkpoints = stored(whole)
    assert (status, len(individuals), len(checkpoints)) == ("finished", 24, 4)
    with RunStore(whole) as store:
        (info,) = store.runs()
    song = folder / "song.wav"
    assert info.kind == "gp-luxo" and info.config["task"] == "luxo-dance"
    assert info.song_hash == hashlib.sha256(song.read_bytes()).hexdigest()
    assert info.song_path == str(song.resolve())
    assert {"sin", "cos"} <= set(info.config["functions"])
    assert list(individuals[0].terms or {}) == ["lift", "head", "fallen", "spot", "joints",
                                                "smooth"]  # fmt: skip
    lifts = {round(float((ind.terms or {})["lift"] or 0.0), 6) for ind in individuals}
    assert len(lifts) > 3  # programs dance differently to the beat
    with RunStore(whole) as store:
        plot = fitness_plot(store, info.id)
    assert plot.title.endswith("\nfitness (beat lift + style)")  # not the hop's distance label


def test_a_killed_dance_resumes_to_the_uninterrupted_one(folder: Path, whole: Path) -> None:
    cut = folder / "cut.db"
    kill_when(arguments(folder, "cut.db"), cut, 2)
    assert 2 <= stored_generations(cut) < 4
    resumed = subprocess.run([*sinews_command(), "runs", "resume", "1", "--db", str(cut)],
                             capture_output=True, text=True, check=False)  # fmt: skip
    assert resumed.returncode == 0, resumed.stderr[-2000:]
    assert stored(cut) == stored(whole)


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
