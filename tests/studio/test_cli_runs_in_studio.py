"""Runs made by the installed ``sinews`` opened in the studio, and studio runs seen from the CLI.

One protocol serves both (`sinews.experiments.kinds`): a hybrid dancer run
started by ``sinews evolve dancers`` is continued by picks on a real studio
server, and a studio run's tempo correction is honoured when the CLI replays it.
"""

from __future__ import annotations

import json
import subprocess
import urllib.request
from pathlib import Path

import numpy as np

from killed_runs import sinews_command
from sinews.experiments.dancers.run import run_music
from sinews.music import analyse_file, shift_beats
from sinews.store import RunStore
from sinews.studio.service import StudioSettings, Worker
from sinews.trajectory import Trajectory
from studio_helpers import StudioServer


def _sinews(env: dict[str, str], *args: str) -> subprocess.CompletedProcess[str]:
    command = [*sinews_command(), *args]
    return subprocess.run(command, capture_output=True, text=True, env=env, timeout=300)


def _post(url: str, body: dict[str, object]) -> bytes:
    origin = url.split("/api/")[0]
    request = urllib.request.Request(
        url, data=json.dumps(body).encode(), method="POST",
        headers={"Content-Type": "application/json", "Origin": origin},
    )  # fmt: skip
    with urllib.request.urlopen(request, timeout=120) as answer:
        assert answer.status == 200
        return bytes(answer.read())


def test_the_studio_continues_a_hybrid_run_made_by_the_cli(
    tmp_path: Path, studio_env: dict[str, str]
) -> None:
    db = tmp_path / "runs.db"
    made = _sinews(studio_env, "evolve", "dancers", "--song", "demo:groove", "--population",
                   "6", "--generations", "2", "--seconds", "2", "--strategy", "hybrid",
                   "--executor", "serial", "--db", str(db))  # fmt: skip
    assert made.returncode == 0, made.stderr
    server = StudioServer(db, studio_env, "--resume", "1")
    try:
        assert server.run_id == 1
        with urllib.request.urlopen(server.url + "api/runs", timeout=60) as answer:
            runs = json.loads(answer.read())
        assert [run["id"] for run in runs] == [1]
        _post(server.url + "api/runs/1/generations/1/breed", {"picks": [2, 4], "mutation": 0.1})
    finally:
        server.stop()
    with RunStore(db, readonly=True) as store:
        assert store.run(1).generations == 3
        picked = [p.index for p in store.individuals(1, 1) if p.picked]
        newest = store.individuals(1, 2)
        assert picked == [2, 4]
        assert all(p.fitness is not None for p in newest)  # hybrid: the children are scored
        assert any(set(p.parents) & {store.individuals(1, 1)[k].id for k in picked}
                   for p in newest)  # fmt: skip
    shown = _sinews(studio_env, "runs", "show", "1", "--db", str(db))
    assert shown.returncode == 0 and "hybrid" in shown.stdout


def test_a_tempo_corrected_studio_run_replays_at_its_tempo_in_the_cli(
    tmp_path: Path, studio_home: None, studio_env: dict[str, str]
) -> None:
    db = tmp_path / "studio.db"
    worker = Worker(StudioSettings(db=db))
    try:
        run = worker.call(lambda s: s.start())
        analysed = worker.call(lambda s: s.runs.music(run)[0].tempo_bpm)
        corrected = round(analysed * 2 / 3, 1)  # a 2:3 correction the ×2 / ÷2 buttons cannot make
        worker.call(lambda s: s.runs.set_bpm(run, corrected))
        worker.call(lambda s: s.runs.set_beat_shift(run, 0.25))
        dancer = worker.call(lambda s: s.store.individuals(run, 0)[3].id)
        song = worker.call(lambda s: s.runs.music(run)[1])
    finally:
        worker.close()
    motion = tmp_path / "motion.npz"
    rendered = _sinews(studio_env, "render", str(run), "--individual", str(dancer), "-o",
                       str(motion), "--db", str(db))  # fmt: skip
    assert rendered.returncode == 0, rendered.stderr
    beats = Trajectory.load(motion).beats
    assert beats is not None
    expected = shift_beats(analyse_file(song, bpm=corrected), 0.25).beats
    np.testing.assert_array_equal(beats, expected)
    assert not np.array_equal(beats[: len(expected)], analyse_file(song).beats[: len(expected)])
    with RunStore(db, readonly=True) as store:
        music, _ = run_music(store.run(run))
    assert music.tempo_bpm == corrected
    scored = _sinews(studio_env, "score", str(motion))
    assert scored.returncode == 0 and "music beats" in scored.stdout
