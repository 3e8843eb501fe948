"""Timing helpers shared by the benchmarks."""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass

__all__ = ["Measurement", "best_time"]


@dataclass(frozen=True)
class Measurement:
    """One benchmark case: our rate against a reference rate from the same run.

    Attributes:
        case: what was measured, e.g. ``"P=2000 x 600 steps"``.
        unit: unit of both rates, e.g. ``"node-steps/s"`` (higher is better).
        ours: our rate.
        reference: the reference's rate, or NaN when there is none.
        reference_name: what the reference is, e.g. ``"numpy reference"``.
    """

    case: str
    unit: str
    ours: float
    reference: float
    reference_name: str

    @property
    def ratio(self) -> float:
        """ours / reference (how many times faster we are)."""
        return self.ours / self.reference if self.reference > 0 else float("nan")


def best_time(fn: Callable[[], object], repeats: int = 3) -> float:
    """Seconds of the fastest of ``repeats`` calls of ``fn`` (after none warm-up)."""
    best = float("inf")
    for _ in range(repeats):
        start = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - start)
    return best
