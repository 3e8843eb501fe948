"""Killing a CLI run mid-way: run ``sinews`` in a subprocess, SIGKILL it once enough is stored."""

from __future__ import annotations

import os
import signal
import sqlite3
import subprocess
import sys
import time
from pathlib import Path

__all__ = ["alive", "descendants", "kill_when", "sinews_command", "stored_generations"]


def sinews_command() -> list[str]:
    """The installed ``sinews`` script of this interpreter's environment."""
    return [str(Path(sys.executable).with_name("sinews"))]


def descendants(pid: int) -> set[int]:
    """Every live process below ``pid`` (children, their children...), read from /proc."""
    parents: dict[int, int] = {}
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                stat = (entry / "stat").read_text()
            except OSError:
                continue
            parents[int(entry.name)] = int(stat.rsplit(")", 1)[1].split()[1])
    found: set[int] = set()
    frontier = {pid}
    while frontier:
        frontier = {child for child, parent in parents.items() if parent in frontier} - found
        found |= frontier
    return found


def alive(pid: int) -> bool:
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except OSError:
        return False
    return state != "Z"


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
    Fails if the run ended before it could be killed, or if any process it
    started (pool workers, the resource tracker) outlives it by more than 10 s.
    """
    proc = subprocess.Popen([*sinews_command(), *args],
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)  # fmt: skip
    while stored_generations(db) < generations and proc.poll() is None:
        time.sleep(0.002)
    children = descendants(proc.pid)
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    assert proc.returncode == -signal.SIGKILL, "the run finished before it could be killed"
    for _ in range(1000):
        left = {pid for pid in children if alive(pid)}
        if not left:
            break
        time.sleep(0.01)
    assert not left, f"processes left behind by the killed run: {sorted(left)}"
