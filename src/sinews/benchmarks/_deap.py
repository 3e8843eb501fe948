"""Our GP programs as DEAP users would run them: primitive trees compiled to lambdas.

DEAP (https://github.com/DEAP/deap) stores a tree as a list of primitives and
terminals in prefix order, as we do, so a `Tree` converts node for node. The
functions are plain Python ones with our semantics (protected division,
``ifltz``, NaN-aware min/max), as in DEAP's symbolic-regression example; each
tree is turned into a Python lambda by ``deap.gp.compile`` and called once per
individual and tree with the individual's terminal values as scalars (a closed
loop evaluates one input row per individual per tick, so there is nothing to
vectorise over). Breeding is DEAP's too: tournaments of 7 (``tools.selTournament``),
one-point crossover of one tree slot with probability 0.9 (``gp.cxOnePoint``) and
uniform mutation of one slot with probability 0.1 (``gp.mutUniform``), the way
DEAP's multi-tree (ADF) example breeds. Only benchmarks import this module.
"""

from __future__ import annotations

import copy
import math
import operator
import random
from collections.abc import Callable, Sequence
from functools import partial
from typing import Any

import numpy as np
import numpy.typing as npt

from sinews.control.gp import GPController, Program, Wiring
from sinews.control.gp.primitives import CONST, DIVISION_EPSILON, FUNCTIONS, VAR, PrimitiveSet

__all__ = ["DeapController", "DeapPopulation"]

FloatArray = npt.NDArray[np.float64]
Compiled = Callable[..., float]


def _div(a: float, b: float) -> float:
    return 1.0 if abs(b) < DIVISION_EPSILON else a / b


def _ifltz(a: float, b: float, c: float) -> float:
    return b if a < 0.0 else c


def _finite(f: Callable[[float], float]) -> Callable[[float], float]:
    """``f`` answering NaN where ``math`` would raise (cos(inf))."""

    def safe(x: float) -> float:
        return f(x) if math.isfinite(x) else math.nan

    safe.__name__ = f.__name__
    return safe


_PYTHON: dict[str, Callable[..., float]] = {
    "+": operator.add,
    "-": operator.sub,
    "*": operator.mul,
    "%": _div,
    "ifltz": _ifltz,
    "cos": _finite(math.cos),
    "sin": _finite(math.sin),
    "abs": abs,
    "min": lambda a, b: a if a < b else b,
    "max": lambda a, b: a if a > b else b,
}
_NAMES = {"+": "add", "-": "sub", "*": "mul", "%": "pdiv"}


class DeapPopulation:
    """P programs of J trees as DEAP ``PrimitiveTree``s and their compiled lambdas.

    Args:
        programs: P programs of J trees.
        pset: their primitive set (V terminals become DEAP arguments ARG0..ARG{V-1}).
    """

    def __init__(self, programs: Sequence[Program], pset: PrimitiveSet) -> None:
        from deap import gp

        self._gp = gp
        self.pset = gp.PrimitiveSet("MAIN", pset.n_terminals)
        by_code: dict[int, Any] = {}
        for symbol in pset.functions:
            code, arity = FUNCTIONS[symbol]
            self.pset.addPrimitive(_PYTHON[symbol], arity, name=_NAMES.get(symbol, symbol))
            by_code[code] = self.pset.primitives[self.pset.ret][-1]
        for k, argument in enumerate(self.pset.arguments):
            by_code[VAR + k] = next(t for t in self.pset.terminals[self.pset.ret]
                                    if t.name == argument)  # fmt: skip
        self.trees = [[self._convert(tree.code, tree.consts, by_code) for tree in program]
                      for program in programs]  # fmt: skip
        self.functions: list[list[Compiled]] = []

    def _convert(self, code: npt.NDArray[np.int32], consts: FloatArray, by_code: dict) -> Any:
        constants = iter(consts.tolist())
        nodes = [
            self._gp.Terminal(next(constants), False, object) if c == CONST else by_code[c]
            for c in code.tolist()
        ]
        return self._gp.PrimitiveTree(nodes)

    def compile(self) -> None:
        """``gp.compile`` every tree (what a DEAP run does before rating an individual)."""
        self.functions = [[self._gp.compile(tree, self.pset) for tree in program]
                          for program in self.trees]  # fmt: skip

    def breed(self, fitness: FloatArray, seed: int) -> list[list[Any]]:
        """The next generation's trees, bred by DEAP's operators from (P,) ``fitness``.

        DEAP draws from Python's global `random`, seeded here with ``seed``.
        """
        from deap import base, creator, tools

        if not hasattr(creator, "SinewsIndividual"):
            creator.create("SinewsFitness", base.Fitness, weights=(1.0,))
            creator.create("SinewsIndividual", list, fitness=creator.SinewsFitness)
        random.seed(seed)
        rated = []
        for trees, value in zip(self.trees, fitness.tolist(), strict=True):
            individual = creator.SinewsIndividual(trees)
            individual.fitness.values = (value,)
            rated.append(individual)
        offspring = [copy.deepcopy(ind) for ind in tools.selTournament(rated, len(rated), 7)]
        for a, b in zip(offspring[::2], offspring[1::2], strict=False):
            if random.random() < 0.9:
                j = random.randrange(len(a))
                a[j], b[j] = self._gp.cxOnePoint(a[j], b[j])
        grow = partial(self._gp.genFull, pset=self.pset, min_=0, max_=2)
        for trees in offspring:
            if random.random() < 0.1:
                j = random.randrange(len(trees))
                (trees[j],) = self._gp.mutUniform(trees[j], expr=grow, pset=self.pset)
        return offspring

    def evaluate(self, inputs: FloatArray, out: FloatArray) -> FloatArray:
        """(P, J) tree values on each individual's (P, V) input row, into ``out``."""
        for p, (row, functions) in enumerate(zip(inputs.tolist(), self.functions, strict=True)):
            for j, function in enumerate(functions):
                out[p, j] = function(*row)
        return out


class DeapController(GPController):
    """`GPController` whose trees are DEAP-compiled lambdas (same wiring, clipping and NaNs)."""

    def __init__(self, programs: Sequence[Program], wiring: Wiring, pset: PrimitiveSet) -> None:
        super().__init__(programs, wiring)
        self.deap = DeapPopulation(programs, pset)
        self.deap.compile()

    def _tree_values(self, inputs: FloatArray) -> FloatArray:
        return self.deap.evaluate(inputs, self._values)
