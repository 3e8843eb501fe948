"""The error raised for a database the store cannot or will not use."""

from __future__ import annotations

from sinews.errors import SinewsError

__all__ = ["StoreError"]


class StoreError(SinewsError):
    """A corrupt, foreign or too-new database, a missing run, or a bad genome blob."""
