"""The force-directed spring-mass engine of seed 000, batched over a population.

`Body` describes one graph of nodes and springs; `BodyBatch` pads many into
P x N arrays; `simulate` runs the paper's six-step frame loop on them with a
numba kernel (or the plain-numpy reference) and records the motion.
"""

from __future__ import annotations

from sinews.springmass.batch import BodyBatch, EngineParams, SimState, Status
from sinews.springmass.body import Body, BodyError
from sinews.springmass.engine import Backend, Recording, simulate

__all__ = [
    "Backend",
    "Body",
    "BodyBatch",
    "BodyError",
    "EngineParams",
    "Recording",
    "SimState",
    "Status",
    "simulate",
]
