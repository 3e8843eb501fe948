"""The error raised when a strategy is misused or a checkpoint cannot be read."""

from __future__ import annotations

from sinews.errors import SinewsError

__all__ = ["StrategyError"]


class StrategyError(SinewsError):
    """Misuse of a strategy (tell before ask, wrong sizes) or a bad checkpoint."""
