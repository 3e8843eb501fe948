"""Helpers shared by the GP tests: a primitive set, random populations, seeds, stored runs."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from hypothesis import strategies as st

from sinews.control.gp import (
    BASIC_FUNCTIONS,
    EXTRA_FUNCTIONS,
    PrimitiveSet,
    Program,
    ramped_half_and_half,
)
from sinews.store import Individual, RunStore

TERMINALS = ("time", "gx", "q_a", "q_b")


def make_pset(extras: bool = False) -> PrimitiveSet:
    functions = BASIC_FUNCTIONS + (EXTRA_FUNCTIONS if extras else ())
    return PrimitiveSet(TERMINALS, functions=functions, erc_range=(-5.0, 5.0))


seeds = st.integers(0, 2**32 - 1)


def population(seed: int, n: int, n_trees: int = 3, extras: bool = False) -> list[Program]:
    """``n`` random programs from ``seed`` (depths 0 to 6)."""
    rng = np.random.default_rng(seed)
    pset = make_pset(extras)
    return ramped_half_and_half(pset, rng, n_programs=n, n_trees=n_trees, min_depth=0, max_depth=6)


def stored(db: Path) -> tuple[str, list[Individual], list[bytes]]:
    """A database's only run: its status, individuals (genomes, fitness, terms, lineage)
    and strategy checkpoints, for bit-for-bit comparison."""
    with RunStore(db) as store:
        (info,) = store.runs()
        checkpoints = [store.checkpoint(info.id, g) for g in range(info.generations)]
        return info.status, store.individuals(info.id), checkpoints
