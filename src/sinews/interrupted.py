"""Ctrl-C where no clean exit is possible: say so in one line and exit 130 at once."""

from __future__ import annotations

import os

__all__ = ["exit_interrupted"]


def exit_interrupted(signum: int, frame: object) -> None:
    """A SIGINT handler: say "interrupted" and exit 130 at once (no cleanup, no traceback)."""
    os.write(2, b"interrupted\n")
    os._exit(130)
