"""Writing output files atomically, with one-line errors."""

from __future__ import annotations

import os
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

from sinews.files import atomic_path
from sinews.render.errors import RenderError

__all__ = ["atomic_output", "suffix_of"]


def suffix_of(path: str | os.PathLike[str], allowed: tuple[str, ...]) -> str:
    """The lower-case suffix of ``path`` (e.g. ``".png"``); RenderError if not ``allowed``."""
    suffix = Path(path).suffix.lower()
    if suffix not in allowed:
        shown = f"'{suffix}'" if suffix else "no suffix"
        raise RenderError(f"{path}: cannot write {shown}; use one of {', '.join(allowed)}")
    return suffix


@contextmanager
def atomic_output(path: str | os.PathLike[str]) -> Iterator[Path]:
    """Yield a temporary path next to ``path``; move it into place if the block succeeds.

    Readers never see a half-written file. An `OSError` in the block (missing
    or read-only directory, full disk) becomes a `RenderError`; on any error
    the temporary file is removed. A missing or read-only directory is
    reported before any work is done by the caller's block.
    """
    path = Path(path)
    parent = path.parent
    if not parent.is_dir():
        raise RenderError(f"cannot write {path}: {parent} is not a directory")
    if not os.access(parent, os.W_OK):
        raise RenderError(f"cannot write {path}: {parent} is not writable")
    try:
        with atomic_path(path) as tmp:
            yield tmp
    except OSError as exc:
        raise RenderError(f"cannot write {path}: {exc.strerror or exc}") from None
