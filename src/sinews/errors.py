"""The user-facing error type: anything the CLI or studio reports in one line.

The rule (as pyribs keeps it): `SinewsError` and its subclasses are for what a
*user* can cause — a bad file, option, song, setting or environment — and carry
a one-line reason the CLI prints before exiting 2. Programmer misuse of the
library (calling ``tell`` before ``ask``, wrong array shapes, a kind registered
with a bad name) raises plain `ValueError`, `TypeError` or `RuntimeError`,
which the CLI does not dress up: they are bugs, and show a traceback.
"""

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
