"""Benchmarks run by ``sinews bench NAME``.

Each module ``sinews.benchmarks.NAME`` defines ``run(scale: Scale = "full") ->
list[Result]``: every measurement compares our code with a reference measured
in the same run, so the ratio means something on any machine. Where the
reference is another tool (DEAP, Taichi, librosa: the ``[bench]`` extra) and
that tool is not installed, the case comes back as `Skipped` with the reason.
"""

from __future__ import annotations

from sinews.benchmarks._measure import (
    Measurement,
    Result,
    Scale,
    Skipped,
    best_time,
    optional,
)

__all__ = ["Measurement", "Result", "Scale", "Skipped", "best_time", "optional"]
