"""Evaluating a population of programs: the packed numba interpreter and a numpy reference.

`PackedPopulation` concatenates every individual's trees once per generation
(the stored form); its first `evaluate` translates them into the register
machine of `sinews.control.gp.kernels`, and every call then answers all (P,
J) tree values for a (P, V) input array in one numba call (serial by
default, or parallel over individuals). The
reference, `reference_tree`, evaluates one tree with numpy over many input
rows by recursion on the prefix codes; it defines the semantics the kernel
must match and is kept for tests and benchmarks.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property

import numpy as np
import numpy.typing as npt

from sinews.control.gp import kernels
from sinews.control.gp.primitives import (
    ABS,
    ADD,
    ARITY,
    CONST,
    COS,
    DIV,
    DIVISION_EPSILON,
    IFLTZ,
    MAX,
    MIN,
    MUL,
    SIN,
    SUB,
    VAR,
    GPError,
)
from sinews.control.gp.tree import Program, Tree

__all__ = ["PackedPopulation", "reference_population", "reference_tree"]

FloatArray = npt.NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class PackedPopulation:
    """P programs of J trees each, concatenated for the interpreter.

    Attributes:
        code: (N,) int32 every tree's codes, individual-major, slot-minor.
        consts: (C,) float64 every tree's constants, in the same order.
        tree_start: (P·J + 1,) int64 first node of each tree, then N.
        const_start: (P·J + 1,) int64 first constant of each tree, then C.
        n_programs: P.
        n_trees: J.
    """

    code: npt.NDArray[np.int32]
    consts: FloatArray
    tree_start: npt.NDArray[np.int64]
    const_start: npt.NDArray[np.int64]
    n_programs: int
    n_trees: int

    @classmethod
    def pack(cls, programs: Sequence[Program]) -> PackedPopulation:
        """Pack programs that all have the same number of trees."""
        if not programs:
            raise GPError("cannot pack an empty population")
        n_trees = len(programs[0])
        if any(len(program) != n_trees for program in programs):
            raise GPError("every program needs the same number of trees")
        trees = [tree for program in programs for tree in program]
        lengths = [len(tree) for tree in trees]
        n_consts = [len(tree.consts) for tree in trees]
        return cls(
            code=np.concatenate([tree.code for tree in trees]),
            consts=np.concatenate([tree.consts for tree in trees]),
            tree_start=np.concatenate([[0], np.cumsum(lengths)]).astype(np.int64),
            const_start=np.concatenate([[0], np.cumsum(n_consts)]).astype(np.int64),
            n_programs=len(programs),
            n_trees=n_trees,
        )

    @cached_property
    def _terminals_read(self) -> int:
        """One more than the highest terminal column any tree reads (0 if none)."""
        return max(0, int(self.code.max()) - VAR + 1)

    @cached_property
    def _machine(self) -> tuple[npt.NDArray[np.uint32], npt.NDArray[np.int64],
                                npt.NDArray[np.int64], FloatArray]:  # fmt: skip
        """`kernels.translate`'s instructions, first and result, and the slots (constants
        filled in)."""
        trees, longest = self.n_programs * self.n_trees, int(np.diff(self.tree_start).max())
        most = self.n_programs * self._terminals_read + self.consts.size + trees * longest
        if most >= 2**32:  # the kernels index slots with uint32
            raise GPError(f"a population of {self.code.size} nodes is too large to evaluate")
        instructions, first, result, n_slots = kernels.translate(
            self.code, self.tree_start, self.const_start, self.n_trees, self._terminals_read
        )
        slots = np.zeros(n_slots)
        const_base = self.n_programs * self._terminals_read
        slots[const_base : const_base + self.consts.size] = self.consts
        return instructions, first, result, slots

    def evaluate(
        self, inputs: FloatArray, out: FloatArray | None = None, *, parallel: bool = False
    ) -> FloatArray:
        """Every tree's value on its individual's input row.

        Args:
            inputs: (P, V) terminal values; V must cover every terminal used.
            out: optional (P, J) float64 destination.
            parallel: use the parallel kernel (not inside a MuJoCo rollout: see
                `sinews.control.gp.kernels`).

        Returns:
            (P, J) tree values (non-finite where the arithmetic overflowed).
        """
        shape = (self.n_programs, self.n_trees)
        rows = np.asarray(inputs, dtype=np.float64)
        if rows.ndim != 2 or rows.shape[0] != self.n_programs:
            raise GPError(f"inputs must have shape ({self.n_programs}, V), got {rows.shape}")
        if self._terminals_read > rows.shape[1]:
            raise GPError(
                f"the trees read {self._terminals_read} terminals, inputs have {rows.shape[1]}"
            )
        result = np.empty(shape) if out is None else out
        run = kernels.evaluate if parallel else kernels.evaluate_serial
        instructions, first, tree_slot, slots = self._machine
        read = np.ascontiguousarray(rows[:, : self._terminals_read])  # one numba signature
        run(instructions, first, tree_slot, read, slots, result)
        return result


def reference_tree(tree: Tree, inputs: FloatArray) -> FloatArray:
    """A tree's value on each input row, with numpy (the interpreter's specification).

    Args:
        tree: the tree.
        inputs: (n, V) terminal values.

    Returns:
        (n,) values.
    """
    rows = np.asarray(inputs, dtype=np.float64)
    constants = iter(tree.consts.tolist())
    codes = iter(tree.code.tolist())

    def value() -> FloatArray:
        op = next(codes)
        if op >= VAR:
            return rows[:, op - VAR].copy()
        if op == CONST:
            return np.full(len(rows), next(constants))
        args = [value() for _ in range(int(ARITY[op]))]
        return _apply(op, args)

    with np.errstate(all="ignore"):
        return value()


def _apply(op: int, args: list[FloatArray]) -> FloatArray:
    if op == IFLTZ:
        return np.where(args[0] < 0.0, args[1], args[2])
    if op in (COS, SIN, ABS):
        return {COS: np.cos, SIN: np.sin, ABS: np.abs}[op](args[0])
    a, b = args
    if op == DIV:
        return np.where(np.abs(b) < DIVISION_EPSILON, 1.0, a / b)
    if op == MIN:
        return np.where(a < b, a, b)
    if op == MAX:
        return np.where(a > b, a, b)
    return {ADD: np.add, SUB: np.subtract, MUL: np.multiply}[op](a, b)


def reference_population(programs: Sequence[Program], inputs: FloatArray) -> FloatArray:
    """`PackedPopulation.evaluate` done tree by tree with `reference_tree`: (P, V) → (P, J)."""
    rows = np.asarray(inputs, dtype=np.float64)
    return np.array(
        [
            [reference_tree(tree, rows[p : p + 1])[0] for tree in program]
            for p, program in enumerate(programs)
        ]
    )
