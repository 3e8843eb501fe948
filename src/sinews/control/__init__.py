"""Controllers for articulated figures: the `Controller` protocol and its implementations.

`springnet` is the spring-net controller of seed 001; `HoldPose` holds fixed
targets (the rest pose, a test step).
"""

from __future__ import annotations

from sinews.control.hold import HoldPose
from sinews.control.protocol import Controller

__all__ = ["Controller", "HoldPose"]
