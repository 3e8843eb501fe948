"""A run's lease: one process evolves a run at a time, and a killed holder lets go."""

from __future__ import annotations

import signal
import subprocess
import sys
from pathlib import Path

import pytest

from sinews.store import StoreError
from sinews.store.lease import leased, run_lease

HOLD = """
import sys, time
from pathlib import Path
from sinews.store.lease import run_lease
with run_lease(Path(sys.argv[1]) / "runs.db", 7):
    print("held", flush=True)
    time.sleep(600)
"""


def test_one_holder_at_a_time_and_the_lease_ends_with_the_block(tmp_path: Path) -> None:
    db = tmp_path / "runs.db"
    assert not leased(db, 7)
    with run_lease(db, 7):
        assert leased(db, 7) and not leased(db, 8)
        refused = pytest.raises(StoreError, match="run 7 is being run by another process")
        with refused, run_lease(db, 7):
            pass
        assert leased(db, 7)  # the refused attempt and the probe took nothing away
    assert not leased(db, 7)


def test_two_databases_in_one_folder_lease_their_runs_apart(tmp_path: Path) -> None:
    with run_lease(tmp_path / "a.db", 1):
        assert not leased(tmp_path / "b.db", 1)
        with run_lease(tmp_path / "b.db", 1):
            assert leased(tmp_path / "a.db", 1) and leased(tmp_path / "b.db", 1)


def test_a_killed_holder_lets_go(tmp_path: Path) -> None:
    db = tmp_path / "runs.db"
    holder = subprocess.Popen([sys.executable, "-c", HOLD, str(tmp_path)],
                              stdout=subprocess.PIPE, text=True)  # fmt: skip
    try:
        assert holder.stdout is not None and holder.stdout.readline() == "held\n"
        assert leased(db, 7)
        with pytest.raises(StoreError), run_lease(db, 7):
            pass
    finally:
        holder.send_signal(signal.SIGKILL)
        holder.wait(timeout=60)
    assert not leased(db, 7)
    with run_lease(db, 7):
        assert leased(db, 7)
