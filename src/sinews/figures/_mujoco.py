"""The one place that imports MuJoCo, so that a missing extra fails with a clear message."""

from __future__ import annotations

from types import ModuleType

from sinews.errors import SinewsError, missing_extra

__all__ = ["require_mujoco"]


def require_mujoco() -> ModuleType:
    """Return the ``mujoco`` module, or raise the error naming the ``figures`` extra.

    Raises:
        SinewsError: mujoco is not installed, or ``MUJOCO_GL`` names no back end.
    """
    try:
        import mujoco
        import mujoco.batch
    except ImportError:
        raise missing_extra("mujoco", "figures") from None
    except RuntimeError as exc:  # MuJoCo checks MUJOCO_GL as it loads
        raise SinewsError(f"cannot load MuJoCo ({exc}); unset MUJOCO_GL or set it to osmesa, "
                          "egl or glfw") from None  # fmt: skip
    return mujoco
