"""Spring-net controllers (seed 001): point masses on springs whose positions drive joints."""

from __future__ import annotations

from sinews.control.springnet.controller import SpringNetController, stable_time_step
from sinews.control.springnet.dynamics import integrate, integrate_reference
from sinews.control.springnet.genome import (
    MASS_RANGE,
    POSITION_RANGE,
    SPRING_RANGE,
    SpringNetError,
    SpringNetGenome,
)

__all__ = [
    "MASS_RANGE",
    "POSITION_RANGE",
    "SPRING_RANGE",
    "SpringNetController",
    "SpringNetError",
    "SpringNetGenome",
    "integrate",
    "integrate_reference",
    "stable_time_step",
]
