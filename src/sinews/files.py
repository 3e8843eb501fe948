"""Atomic file writes: a reader sees the old file or the whole new one, never half of it."""

from __future__ import annotations

import os
import secrets
from collections.abc import Iterator
from contextlib import contextmanager, suppress
from pathlib import Path

__all__ = ["atomic_path", "write_text"]


@contextmanager
def atomic_path(path: str | os.PathLike[str]) -> Iterator[Path]:
    """Yield a fresh temporary path beside ``path``; move it over ``path`` if the block succeeds.

    The temporary is unique per call (two writers of one file never share it) and
    keeps ``path``'s suffix, so writers that pick a format from the name still
    work. On any error it is removed and the error propagates: each caller turns
    `OSError` into its own one-line error.

    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     target = Path(folder) / "notes.txt"
    ...     with atomic_path(target) as tmp:
    ...         _ = tmp.write_text("whole")
    ...     (target.read_text(), sorted(p.name for p in Path(folder).iterdir()))
    ('whole', ['notes.txt'])
    """
    path = Path(path)
    tmp = path.with_name(f".{path.stem}.{os.getpid()}.{secrets.token_hex(6)}.part{path.suffix}")
    try:
        yield tmp
        os.replace(tmp, path)
    finally:
        with suppress(OSError):
            tmp.unlink()


def write_text(path: str | os.PathLike[str], text: str) -> Path:
    """Write ``text`` (UTF-8) to ``path`` atomically and return the path; `OSError` propagates."""
    with atomic_path(path) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return Path(path)
