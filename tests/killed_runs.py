"""Killing a CLI run mid-way: run ``sinews`` in a subprocess, SIGKILL it once enough is stored."""

from __future__ import annotations

import os
import signal
import sqlite3
import subprocess
import sys
import time
from pathlib import Path

__all__ = ["kill_when", "stored_generations"]


def stored_generations(db: Path) -> int:
    """Generations stored in ``db`` (read-only, so as not to disturb the writer); 0 if none yet."""
    if not db.exists():
        return 0
    try:
        conn = sqlite3.connect(f"file:{db}?mode=ro", uri=True, timeout=5)
        try:
            return int(conn.execute("SELECT count(*) FROM generations").fetchone()[0])
        finally:
            conn.close()
    except sqlite3.OperationalError:  # the schema is not there yet
        return 0


def kill_when(args: list[str], db: Path, generations: int) -> None:
    """Run ``sinews ARGS`` in a subprocess and SIGKILL it once ``db`` holds ``generations``.

    The subprocess inherits the environment (set XDG folders with monkeypatch).
    Fails if the run ended before it could be killed.
    """
    code = "import sys; from sinews.cli import main; sys.exit(main(sys.argv[1:]))"
    proc = subprocess.Popen([sys.executable, "-c", code, *args],
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)  # fmt: skip
    while stored_generations(db) < generations and proc.poll() is None:
        time.sleep(0.002)
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    assert proc.returncode == -signal.SIGKILL, "the run finished before it could be killed"
