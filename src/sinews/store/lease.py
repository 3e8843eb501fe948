"""Which process is running a run: an exclusive `flock` on a small file per run.

A run's ``running`` status says a run was started, not that a process is still
at it: a killed run keeps it. The lease says the latter. `run_lease` holds an
exclusive ``flock`` on ``<database folder>/locks/<database name>-run-<id>.lock``
while a run evolves (named by the database too: two databases in one folder
both have a run 1); the kernel drops it when the holder ends, however it ends (SIGKILL
too). ``flock`` locks belong to one open file, so unlike SQLite's POSIX locks
they are not dropped when the process closes some other descriptor of the file.
"""

from __future__ import annotations

import fcntl
import os
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

from sinews.store.errors import StoreError

__all__ = ["check_free", "leased", "run_lease"]


def _path(db: Path, run_id: int) -> Path:
    db = db.resolve()
    return db.parent / "locks" / f"{db.name}-run-{run_id}.lock"


def _taken(run_id: int) -> StoreError:
    return StoreError(f"run {run_id} is being run by another process")


@contextmanager
def run_lease(db: Path, run_id: int) -> Iterator[None]:
    """Hold the lease of run ``run_id`` of database ``db`` for the block; `StoreError` if
    another holder has it."""
    path = _path(db, run_id)
    try:
        path.parent.mkdir(exist_ok=True)
        handle = os.open(path, os.O_RDWR | os.O_CREAT, 0o644)
    except OSError as exc:
        raise StoreError(f"{path}: cannot take the run's lease ({exc.strerror})") from None
    try:
        try:
            fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            raise _taken(run_id) from None
        yield
    finally:
        os.close(handle)


def leased(db: Path, run_id: int) -> bool:
    """True while some holder (this process included) has the lease of run ``run_id`` of
    database ``db``."""
    try:
        handle = os.open(_path(db, run_id), os.O_RDWR)
    except FileNotFoundError:
        return False
    try:
        fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except BlockingIOError:
        return True
    finally:
        os.close(handle)  # also lets go of the probe's own lock
    return False


def check_free(db: Path, run_id: int) -> None:
    """`StoreError` now if another holder has the lease of run ``run_id`` of ``db`` (before
    any work)."""
    if leased(db, run_id):
        raise _taken(run_id)
