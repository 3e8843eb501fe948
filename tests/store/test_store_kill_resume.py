"""A run killed with SIGKILL at any moment resumes to exactly the uninterrupted result."""

from __future__ import annotations

import os
import signal
import sqlite3
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

import pytest

from sinews.cli import main
from sinews.store import RunStore

SONG = str(Path(__file__).resolve().parents[1] / "data" / "loop_mika.flac")
SETTINGS = ["--song", SONG, "--population", "6", "--generations", "24", "--seed", "5",
            "--seconds", "3", "--phase-in", "2:6", "--executor", "serial"]  # fmt: skip


def stored_generations(db: Path) -> int:
    if not db.exists():
        return 0
    try:
        conn = sqlite3.connect(f"file:{db}?mode=ro", uri=True, timeout=5)
        try:
            return int(conn.execute("SELECT count(*) FROM generations").fetchone()[0])
        finally:
            conn.close()
    except sqlite3.OperationalError:
        return 0


def kill_when(args: list[str], db: Path, generations: int, env: dict[str, str]) -> None:
    """Run the CLI in a subprocess and SIGKILL it once ``generations`` are stored."""
    code = "import sys; from sinews.cli import main; sys.exit(main(sys.argv[1:]))"
    proc = subprocess.Popen([sys.executable, "-c", code, *args], env=env,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)  # fmt: skip
    deadline = time.monotonic() + 60
    while stored_generations(db) < generations and proc.poll() is None:
        assert time.monotonic() < deadline, "the run did not get going"
        time.sleep(0.002)
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    assert proc.returncode == -signal.SIGKILL, "the run finished before it could be killed"


def contents(db: Path) -> list[tuple[Any, ...]]:
    with RunStore(db) as store:
        (info,) = store.runs()
        rows = [(info.status, info.generations)]
        for ind in store.individuals(info.id):
            rows.append((ind.generation, ind.index, ind.genome.tobytes(), ind.seed, ind.fitness,
                         ind.terms, ind.failed, len(ind.parents)))  # fmt: skip
        rows += [store.checkpoint(info.id, g) for g in range(info.generations)]  # type: ignore[misc]
    return rows


@pytest.mark.slow
def test_sigkill_then_resume_gives_the_uninterrupted_run(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("XDG_DATA_HOME", str(tmp_path / "data"))
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    reference, victim = tmp_path / "reference.db", tmp_path / "victim.db"
    assert main(["evolve", "dancers", *SETTINGS, "--db", str(reference)]) == 0

    env = {**os.environ}
    kill_when(["evolve", "dancers", *SETTINGS, "--db", str(victim)], victim, 2, env)
    first = stored_generations(victim)
    assert 2 <= first < 24
    with RunStore(victim) as store:
        assert store.runs()[0].status == "running"
    kill_when(["runs", "resume", "1", "--executor", "serial", "--db", str(victim)], victim,
              first + 3, env)  # fmt: skip
    assert first + 3 <= stored_generations(victim) < 24
    assert main(["runs", "resume", "1", "--executor", "serial", "--db", str(victim)]) == 0

    assert contents(victim) == contents(reference)
