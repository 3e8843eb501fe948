"""Timing helpers shared by the benchmarks."""

from __future__ import annotations

import importlib
import time
from collections.abc import Callable
from dataclasses import dataclass
from types import ModuleType
from typing import Literal

__all__ = ["Measurement", "Result", "Scale", "Skipped", "best_time", "optional"]

Scale = Literal["full", "quick", "tiny"]
"""How big the cases are (``sinews bench --scale``): ``full`` for the numbers in
BENCHMARKS.md, ``quick`` for a look, ``tiny`` to check that a benchmark runs (its
rates mean little)."""


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


@dataclass(frozen=True)
class Skipped:
    """A case that could not run, e.g. because its reference tool is not installed.

    Attributes:
        case: what would have been measured.
        reason: one line, e.g. ``"deap is not installed (pip install 'sinews[bench]')"``.
    """

    case: str
    reason: str


Result = Measurement | Skipped


def optional(module: str, case: str) -> ModuleType | Skipped:
    """Import an anchor's tool from the ``[bench]`` extra, or say why ``case`` is skipped."""
    try:
        return importlib.import_module(module)
    except ImportError:
        return Skipped(case, f"{module} is not installed (pip install 'sinews[bench]')")


def best_time(fn: Callable[[], object], repeats: int = 3) -> float:
    """Seconds of the fastest of ``repeats`` calls of ``fn`` (after none warm-up)."""
    best = float("inf")
    for _ in range(repeats):
        start = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - start)
    return best
