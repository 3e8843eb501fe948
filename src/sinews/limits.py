"""The sizes sinews accepts: bounded input means bounded memory and time.

Every limit is checked where the value enters (run settings, loaders, the
studio's requests), with a one-line `SinewsError`; docs/limits.md lists them.
"""

from __future__ import annotations

import math

from sinews.errors import SinewsError

__all__ = [
    "MAX_GENERATIONS",
    "MAX_JSON_BYTES",
    "MAX_JSON_DEPTH",
    "MAX_JSON_DIGITS",
    "MAX_MASSES",
    "MAX_PHYSICS_HZ",
    "MAX_PICTURE_PIXELS",
    "MAX_POPULATION",
    "MAX_RUN_FILE_BYTES",
    "MAX_RUN_ID",
    "MAX_SECONDS",
    "MAX_SEED",
    "MAX_TRAJECTORY_BYTES",
    "MIN_PICTURE_PIXELS",
    "check_number",
    "check_whole",
]

MAX_SECONDS = 20 * 60.0
"""Length of a dance, a scene or a song, seconds."""
MAX_POPULATION = 5000
"""Individuals per generation (the paper's largest spring-net run has 2000)."""
MAX_GENERATIONS = 100_000
MAX_MASSES = 64
"""Point masses per spring net (its time step is stable up to about 60)."""
MAX_PHYSICS_HZ = 100_000
"""Physics steps per simulated second of a figure (the control rate divides it)."""
MIN_PICTURE_PIXELS = 16
MAX_PICTURE_PIXELS = 4096
"""Width or height of a rendered picture or video frame."""
MAX_RUN_ID = 2**63 - 1
MAX_SEED = 2**62
"""A run's seed (a group of runs takes the seeds after it; all fit SQLite's integers)."""
MAX_RUN_FILE_BYTES = 2**20
"""Size of a TOML run file."""
"""SQLite's largest integer: run and individual ids above it cannot exist."""
MAX_JSON_BYTES = 16 * 2**20
MAX_JSON_DEPTH = 64
MAX_JSON_DIGITS = 40
"""Digits of an integer in a genome, run or request document."""
MAX_TRAJECTORY_BYTES = 2 * 2**30
"""Decoded size of all arrays of one trajectory file."""


def check_number(name: str, value: object, low: float, high: float) -> float:
    """``value`` as a float if it is a finite number in [low, high]; else a `SinewsError`."""
    if (
        isinstance(value, bool)
        or not isinstance(value, int | float)
        or not (math.isfinite(value) and low <= value <= high)
    ):
        raise SinewsError(f"{name} must be between {low:g} and {high:g}, got {value!r}")
    return float(value)


def check_whole(name: str, value: object, low: int, high: int) -> int:
    """``value`` if it is an int in [low, high]; else a one-line `SinewsError`."""
    if isinstance(value, bool) or not isinstance(value, int) or not low <= value <= high:
        raise SinewsError(f"{name} must be a whole number from {low} to {high}, got {value!r}")
    return value
