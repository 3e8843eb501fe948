"""The user-facing error type: anything the CLI or studio reports in one line."""

from __future__ import annotations

__all__ = ["SinewsError", "missing_extra"]


class SinewsError(Exception):
    """A problem with the user's input or environment, explained in one line.

    The CLI prints ``error: <message>`` and exits with status 2; the studio
    shows the message. Subclasses name the area (audio, genome, trajectory…).
    """


def missing_extra(module: str, extra: str) -> SinewsError:
    """The error for an optional dependency that is not installed."""
    return SinewsError(f"{module} is not installed; install it with: pip install 'sinews[{extra}]'")
