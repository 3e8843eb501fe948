"""The render package's user-facing error."""

from __future__ import annotations

from sinews.errors import SinewsError

__all__ = ["RenderError"]


class RenderError(SinewsError):
    """A picture, animation or plot that cannot be made, with a one-line reason."""
