"""Every figure dances: a tiny dance of each figure and controller through the installed
``sinews``, stored with the song's hash and the dance's terms, resumed bit for bit after
SIGKILL; bad input refused in one line."""

from __future__ import annotations

import hashlib
import subprocess
from collections.abc import Iterator
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np
import pytest

pytest.importorskip("mujoco")

from dance_helpers import song_folder
from gp_helpers import stored
from killed_runs import kill_when, sinews_command, stored_generations
from render_helpers import decode_audio, probe
from sinews.experiments.gp.run import TASKS
from sinews.experiments.run_files import fitness_plot
from sinews.experiments.springnet.dance import DANCE_FIGURES
from sinews.experiments.springnet.settings import SpringNetSettings
from sinews.figures.tasks import make_task
from sinews.store import RunStore

DANCES = [
    *(("gp", figure) for figure, tasks in TASKS.items() if "dance" in tasks),
    *(("springnet", figure) for figure in DANCE_FIGURES),
]
"""(controller, figure) of every dance the CLI offers."""
RESUMED = [
    case for case in DANCES if case not in (("springnet", "luxo"), ("springnet", "humanoid"))
]
"""Dances killed and resumed: each figure's, and each controller's (the nets' resume is the
same code for every figure, so the snake's stands for them)."""
OPTIONS = ["--task", "dance", "--population", "6", "--generations", "3", "--seconds", "1",
           "--seed", "2"]  # fmt: skip


def dance_name(controller: str, figure: str) -> str:
    """The task a figure's dance is rated by."""
    return TASKS[figure]["dance"][0] if controller == "gp" else DANCE_FIGURES[figure]


@pytest.fixture(scope="module")
def folder(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Path]:
    """A folder with a 2 s song, and the XDG folders (the analysis cache) inside it."""
    where = tmp_path_factory.mktemp("figure_dances")
    with song_folder(where):
        yield where


def arguments(folder: Path, controller: str, figure: str, db: str) -> list[str]:
    return ["evolve", figure, "--controller", controller, *OPTIONS, "--song",
            str(folder / "song.wav"), "--db", str(folder / db)]  # fmt: skip


def sinews(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([*sinews_command(), *args], capture_output=True, text=True,
                          check=False)  # fmt: skip


@pytest.fixture(scope="module")
def dance(request: pytest.FixtureRequest, folder: Path) -> tuple[str, str, Path]:
    """(controller, figure, its database) of an uninterrupted dance run, made once per folder
    (pytest-xdist may set this fixture up again for a case it already made)."""
    controller, figure = request.param
    db = f"{controller}-{figure}.db"
    if not (folder / db).exists():
        done = sinews(*arguments(folder, controller, figure, db))
        assert done.returncode == 0, done.stderr[-2000:]
    return controller, figure, folder / db


@pytest.mark.parametrize("dance", DANCES, indirect=True, ids="-".join)
def test_every_dance_is_stored_with_its_song_and_rated_by_the_beat(
    folder: Path, dance: tuple[str, str, Path]
) -> None:
    controller, figure, db = dance
    status, individuals, checkpoints = stored(db)
    assert (status, len(individuals), len(checkpoints)) == ("finished", 18, 3)
    with RunStore(db) as store:
        (info,) = store.runs()
        plot = fitness_plot(store, info.id)
    song = folder / "song.wav"
    assert info.kind == f"{controller}-{figure}"
    assert info.song_hash == hashlib.sha256(song.read_bytes()).hexdigest()
    assert info.song_path == str(song.resolve())
    task = make_task(dance_name(controller, figure))
    assert list(individuals[0].terms or {}) == list(task.weights)
    lifts = {round(float((ind.terms or {})["lift"] or 0.0), 6) for ind in individuals}
    assert len(lifts) > 3  # they dance differently to the beat
    assert plot.title.endswith("\nfitness (beat lift + style)")  # not the hop's distance label
    if controller == "gp":
        assert info.config["task"] == task.name
        assert {"sin", "cos"} <= set(info.config["functions"])
    else:  # the float GA that takes picks (without them it is the plain GA), on the beat clock
        assert info.config["task"] == "dance" and info.config["strategy"]["name"] == "hybrid"
        assert info.config["clock"] == "beats"
        size = SpringNetSettings.from_values(info.config).genome_size
        assert {len(ind.genome) for ind in individuals} == {size}


@pytest.mark.parametrize("dance", RESUMED, indirect=True, ids="-".join)
def test_a_killed_dance_resumes_to_the_uninterrupted_one(
    folder: Path, dance: tuple[str, str, Path]
) -> None:
    controller, figure, whole = dance
    cut = folder / f"cut-{controller}-{figure}.db"
    kill_when(arguments(folder, controller, figure, cut.name), cut, 1)
    assert 1 <= stored_generations(cut) < 3
    resumed = sinews("runs", "resume", "1", "--db", str(cut))
    assert resumed.returncode == 0, resumed.stderr[-2000:]
    assert contents(cut) == contents(whole)


def contents(db: Path) -> tuple[str, list[Any], list[bytes]]:
    """A run's status, individuals (a net's genes as bytes) and checkpoints, to compare bit
    for bit."""
    status, individuals, checkpoints = stored(db)
    rows = [(ind.genome.tobytes() if isinstance(ind.genome, np.ndarray) else ind.genome,
             replace(ind, genome=None)) for ind in individuals]  # fmt: skip
    return status, rows, checkpoints


@pytest.mark.parametrize("dance", [("gp", "luxo3d"), ("springnet", "snake")], indirect=True,
                         ids="-".join)  # fmt: skip
def test_a_dance_renders_with_its_song(folder: Path, dance: tuple[str, str, Path]) -> None:
    controller, figure, db = dance
    video = folder / f"{controller}-{figure}.mp4"
    done = sinews("render", "1", "--best", "-o", str(video), "--size", "160", "--db", str(db))
    assert done.returncode == 0, done.stderr[-2000:]
    assert "beat lift" in done.stdout
    sound = decode_audio(video, rate=8000)
    assert "Audio: aac" in probe(video) and len(sound) == pytest.approx(8000, rel=0.05)  # 1 s
    assert np.abs(sound).max() > 0.1  # the song, not silence


NET_DANCE = ["luxo", "--controller", "springnet", "--task", "dance", "--song", "song.wav"]
"""A spring-net dance of the lamp to a song (the bad options follow)."""


@pytest.mark.parametrize(
    ("command", "message"),
    [
        (["humanoid3d", "--controller", "gp", "--task", "dance"], "a dance needs a song"),
        (["snake", "--controller", "springnet", "--task", "dance"], "a dance needs a song"),
        (
            ["humanoid", "--controller", "gp", "--task", "reach", "--song", "song.wav"],
            "--song is for the dance task",
        ),
        (
            ["luxo3d", "--controller", "springnet", "--task", "dance", "--song", "song.wav"],
            "spring nets dance only the luxo, snake, humanoid",
        ),
        ([*NET_DANCE, "--tempi", "0.3"], "tempi must be between 0.5 and 2"),
        (["luxo", "--controller", "springnet", "--tempi", "0.8"], "tempi are for a dance"),
        (["luxo", "--controller", "springnet", "--drive", "90"], "a drive is for a dance"),
        ([*NET_DANCE, "--drive", "1e9"], "drive must be a number above 0 and at most 1000"),
        ([*NET_DANCE, "--clock", "sometimes"], "clock must be one of time, beats"),
        (["luxo", "--controller", "springnet", "--clock", "beats"], "a beat clock is for a dance"),
    ],
)
def test_bad_dances_are_one_line(folder: Path, command: list[str], message: str) -> None:
    db = folder / "bad.db"
    done = subprocess.run([*sinews_command(), "evolve", *command, "--db", str(db)],
                          capture_output=True, text=True, check=False, cwd=folder)  # fmt: skip
    err = done.stderr.strip()
    assert done.returncode == 2 and message in err and "\n" not in err, err
    if db.exists():
        with RunStore(db) as store:
            assert store.runs() == []
