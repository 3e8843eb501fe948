"""A process with two connections to one database keeps SQLite's locks (the studio's
background runs open a second `RunStore` beside the worker's)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from sinews.store import RunStore

ADD_AND_LIST = """
import sys
from sinews.store import RunStore
with RunStore(sys.argv[1]) as store:
    if sys.argv[2]:
        store.create_run(sys.argv[2], config={}, seed=0, genome_codec="float64")
    print(" ".join(run.kind for run in store.runs()))
"""


def other_process(db: Path, kind: str = "") -> list[str]:
    done = subprocess.run([sys.executable, "-c", ADD_AND_LIST, str(db), kind],
                          capture_output=True, text=True, check=True, timeout=120)  # fmt: skip
    return done.stdout.split()


def test_a_second_store_in_one_process_does_not_drop_the_first_ones_locks(
    tmp_path: Path,
) -> None:
    db = tmp_path / "runs.db"
    with RunStore(db) as first:
        first.create_run("a", config={}, seed=0, genome_codec="float64")
        RunStore(db).close()  # opened and closed beside the first, in this process
        assert other_process(db, "b") == ["a", "b"]  # another process closes the db last
        assert (tmp_path / "runs.db-wal").exists()  # so it must not have deleted the WAL
        first.create_run("c", config={}, seed=0, genome_codec="float64")
        assert other_process(db) == ["a", "b", "c"]  # what the first writes stays visible
