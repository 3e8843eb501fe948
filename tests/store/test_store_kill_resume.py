"""A run killed with SIGKILL at any moment resumes to exactly the uninterrupted result."""

from __future__ import annotations

from pathlib import Path

import pytest

from killed_runs import kill_when, stored_generations
from sinews.cli import main
from sinews.store import RunStore

SONG = str(Path(__file__).resolve().parents[1] / "data" / "loop_mika.flac")
SETTINGS = ["--song", SONG, "--population", "6", "--generations", "24", "--seed", "5",
            "--seconds", "3", "--phase-in", "2:6", "--executor", "serial"]  # fmt: skip


def contents(db: Path) -> list[object]:
    with RunStore(db) as store:
        (info,) = store.runs()
        rows: list[object] = [(info.status, info.generations)]
        for ind in store.individuals(info.id):
            rows.append((ind.generation, ind.index, ind.genome.tobytes(), ind.seed, ind.fitness,
                         ind.terms, ind.failed, len(ind.parents)))  # fmt: skip
        rows += [store.checkpoint(info.id, g) for g in range(info.generations)]
    return rows


@pytest.mark.slow
def test_sigkill_then_resume_gives_the_uninterrupted_run(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("XDG_DATA_HOME", str(tmp_path / "data"))
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    reference, victim = tmp_path / "reference.db", tmp_path / "victim.db"
    assert main(["evolve", "dancers", *SETTINGS, "--db", str(reference)]) == 0

    kill_when(["evolve", "dancers", *SETTINGS, "--db", str(victim)], victim, 2)
    first = stored_generations(victim)
    assert 2 <= first < 24
    with RunStore(victim) as store:
        assert store.runs()[0].status == "running"
    # killed again while process workers run a generation: none may outlive it
    kill_when(["runs", "resume", "1", "--executor", "processes", "--workers", "2",
               "--db", str(victim)], victim, first + 3)  # fmt: skip
    assert first + 3 <= stored_generations(victim) < 24
    assert main(["runs", "resume", "1", "--executor", "serial", "--db", str(victim)]) == 0

    assert contents(victim) == contents(reference)
