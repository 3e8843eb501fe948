"""Genetic-programming controllers (seed 003): typed expression trees, one per driven joint.

A program is the paper's ``(list t1 ... tJ)``: tree j computes joint j's
desired angle from the terminals (sensors, time, goal-relative position,
ephemeral random constants) with the functions of a per-run `PrimitiveSet`
(``+ - * % ifltz``, optionally ``cos sin abs min max``). Trees are flat int32
prefix codes plus a constant pool (`Tree`); they print and parse as
S-expressions; `GPController` evaluates a whole population's trees each
control tick with a numba interpreter.

Example:
    >>> import numpy as np
    >>> pset = PrimitiveSet(("time", "gx"))
    >>> program = parse_program("(list (% gx 2.0) (ifltz time 0.1 gx))", pset)
    >>> packed = PackedPopulation.pack([program])
    >>> packed.evaluate(np.array([[0.5, 1.0]])).tolist()
    [[0.5, 1.0]]
"""

from __future__ import annotations

from sinews.control.gp.controller import GPController, Wiring
from sinews.control.gp.interpreter import PackedPopulation, reference_population, reference_tree
from sinews.control.gp.operators import (
    Limits,
    crossover,
    leaf_crossover,
    mutate,
    pick_point,
    ramped_half_and_half,
    random_tree,
    tweak_constants,
    within_limits,
)
from sinews.control.gp.primitives import (
    BASIC_FUNCTIONS,
    DIVISION_EPSILON,
    EXTRA_FUNCTIONS,
    FUNCTIONS,
    GPError,
    PrimitiveSet,
)
from sinews.control.gp.sexpr import (
    GENOME_CODEC,
    decode_program,
    encode_program,
    format_program,
    format_tree,
    parse_program,
    parse_tree,
)
from sinews.control.gp.tree import Program, Tree, program_depth, program_size

__all__ = [
    "BASIC_FUNCTIONS",
    "DIVISION_EPSILON",
    "EXTRA_FUNCTIONS",
    "FUNCTIONS",
    "GENOME_CODEC",
    "GPController",
    "GPError",
    "Limits",
    "PackedPopulation",
    "PrimitiveSet",
    "Program",
    "Tree",
    "Wiring",
    "crossover",
    "decode_program",
    "encode_program",
    "format_program",
    "format_tree",
    "leaf_crossover",
    "mutate",
    "parse_program",
    "parse_tree",
    "pick_point",
    "program_depth",
    "program_size",
    "ramped_half_and_half",
    "random_tree",
    "reference_population",
    "reference_tree",
    "tweak_constants",
    "within_limits",
]
