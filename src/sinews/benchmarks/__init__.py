"""Benchmarks run by ``sinews bench NAME``.

Each module ``sinews.benchmarks.NAME`` defines ``run(quick: bool = False) ->
list[Measurement]``: every measurement compares our code with a reference
measured in the same run, so the ratio means something on any machine.
"""

from __future__ import annotations

from sinews.benchmarks._measure import Measurement, best_time

__all__ = ["Measurement", "best_time"]
