"""The one place that imports MuJoCo, so that a missing extra fails with a clear message."""

from __future__ import annotations

from types import ModuleType

from sinews.errors import missing_extra

__all__ = ["require_mujoco"]


def require_mujoco() -> ModuleType:
    """Return the ``mujoco`` module, or raise the error naming the ``figures`` extra.

    Raises:
        SinewsError: mujoco is not installed.
    """
    try:
        import mujoco
        import mujoco.batch
    except ImportError:
        raise missing_extra("mujoco", "figures") from None
    return mujoco
