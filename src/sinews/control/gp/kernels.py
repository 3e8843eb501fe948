"""The numba population interpreter: every individual's trees on its own input row.

Programs are packed end to end (see `sinews.control.gp.interpreter.PackedPopulation`): tree
``t = p·J + j`` (individual p, slot j) is ``code[tree_start[t]:tree_start[t+1]]``
with constants ``consts[const_start[t]:const_start[t+1]]``. A prefix tree is
evaluated by scanning it right to left with a value stack (which is postfix
evaluation without rewriting it): a terminal pushes its value, a function pops
its arguments — the first popped is its first argument — and pushes the result.
A constant is the tree's next one counting down from its pool's end.

`evaluate` runs individuals in parallel; `evaluate_serial` runs the same code on
one thread. Both do the same floating-point operations in the same order, so
they agree bit for bit, and their semantics (see
`sinews.control.gp.primitives`) match the numpy reference in
`sinews.control.gp.interpreter` exactly.

Inside a MuJoCo rollout the serial kernel is the faster. Measured on 2 cores
(Luxo, P = 250, 5 s): a generation took 12.0 s with the parallel kernel and
6.4 s with the serial one, whose 500 calls cost 0.13 s in all. The parallel
kernel's OpenMP threads spin after each call while MuJoCo's threads step:
with ``OMP_WAIT_POLICY=passive`` it took 7.7 s (serial: 6.9 s). The parallel
kernel is for evaluations outside a rollout.
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt
from numba import njit, prange

from sinews.control.gp.primitives import (
    ABS,
    ADD,
    CONST,
    COS,
    DIV,
    DIVISION_EPSILON,
    IFLTZ,
    MIN,
    MUL,
    SIN,
    SUB,
    VAR,
)

__all__ = ["evaluate", "evaluate_serial"]

IntArray = npt.NDArray[np.int32]
IndexArray = npt.NDArray[np.int64]
FloatArray = npt.NDArray[np.float64]


@njit(cache=True, error_model="numpy")
def _run_tree(
    code: IntArray,
    consts: FloatArray,
    start: int,
    stop: int,
    const_stop: int,
    inputs: FloatArray,
    stack: FloatArray,
) -> float:
    """Value of the tree ``code[start:stop]`` on one (V,) input row."""
    top = 0
    c = const_stop
    for i in range(stop - 1, start - 1, -1):
        op = code[i]
        if op >= VAR:
            stack[top] = inputs[op - VAR]
            top += 1
        elif op == CONST:
            c -= 1
            stack[top] = consts[c]
            top += 1
        elif op == IFLTZ:
            top -= 2  # condition at top + 1, then-value at top, else-value at top - 1
            if stack[top + 1] < 0.0:
                stack[top - 1] = stack[top]
        elif op == COS:
            stack[top - 1] = math.cos(stack[top - 1])
        elif op == SIN:
            stack[top - 1] = math.sin(stack[top - 1])
        elif op == ABS:
            stack[top - 1] = abs(stack[top - 1])
        else:
            top -= 1
            a = stack[top]
            b = stack[top - 1]
            if op == ADD:
                r = a + b
            elif op == SUB:
                r = a - b
            elif op == MUL:
                r = a * b
            elif op == DIV:
                r = 1.0 if abs(b) < DIVISION_EPSILON else a / b
            elif op == MIN:
                r = a if a < b else b
            else:  # MAX
                r = a if a > b else b
            stack[top - 1] = r
    return stack[0]


@njit(parallel=True, cache=True, error_model="numpy")
def evaluate(
    code: IntArray,
    consts: FloatArray,
    tree_start: IndexArray,
    const_start: IndexArray,
    inputs: FloatArray,
    out: FloatArray,
    stack: FloatArray,
) -> None:
    """Fill ``out`` (P, J) with every tree's value on its individual's (V,) row of ``inputs``.

    Args:
        code: (N,) packed node codes.
        consts: (C,) packed constants.
        tree_start: (P·J + 1,) first node of each tree, then N.
        const_start: (P·J + 1,) first constant of each tree, then C.
        inputs: (P, V) terminal values.
        out: (P, J) destination.
        stack: (P, L) scratch, L at least the longest tree.
    """
    n_trees = out.shape[1]
    for p in prange(out.shape[0]):
        for j in range(n_trees):
            t = p * n_trees + j
            out[p, j] = _run_tree(
                code, consts, tree_start[t], tree_start[t + 1], const_start[t + 1],
                inputs[p], stack[p],
            )  # fmt: skip


@njit(cache=True, error_model="numpy")
def evaluate_serial(
    code: IntArray,
    consts: FloatArray,
    tree_start: IndexArray,
    const_start: IndexArray,
    inputs: FloatArray,
    out: FloatArray,
    stack: FloatArray,
) -> None:
    """`evaluate` on one thread (same arguments, same results)."""
    n_trees = out.shape[1]
    for p in range(out.shape[0]):
        for j in range(n_trees):
            t = p * n_trees + j
            out[p, j] = _run_tree(
                code, consts, tree_start[t], tree_start[t + 1], const_start[t + 1],
                inputs[p], stack[p],
            )  # fmt: skip
