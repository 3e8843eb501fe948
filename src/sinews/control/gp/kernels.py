"""The numba population interpreter: every individual's trees on its own input row.

Programs are packed end to end (see `sinews.control.gp.interpreter.PackedPopulation`): tree
``t = p·J + j`` (individual p, slot j) is ``code[tree_start[t]:tree_start[t+1]]``
with constants ``consts[const_start[t]:const_start[t+1]]``.

`translate` turns the packed trees, once per population, into a register
machine: one instruction per function node, none per leaf. Every value lives
in one flat (S,) float64 array of slots:

- ``[0, P·V)`` the inputs, individual p's terminal k at ``p·V + k`` (copied in
  per call),
- ``[P·V, P·V + C)`` the constants, in packed order (filled in once),
- ``[P·V + C, S)`` P·J blocks of H temporaries, one block per tree, H the
  tallest stack any tree needs.

An instruction ``(op, a, b, c, dst)`` stores ``op(slots[a], slots[b], slots[c])``
(as many arguments as the function has) in ``slots[dst]``; a leaf operand is
the slot of its input or constant, so a leaf costs no dispatch and no copy. A
tree's instructions are its postfix walk (prefix codes scanned right to left
with a stack of slots; the first argument is the last pushed); a function's
result goes to its tree's temporary at the stack height it leaves.
``result[t]`` is the slot of tree t's value (a leaf's own slot for a lone
leaf). An individual's J trees are dealt out round robin into one stream, so
the CPU overlaps their independent dependency chains.

The opcode of the next instruction is unpredictable, so a branch per opcode
mispredicts about every other node: for the paper's five functions the
kernel computes all five results and picks one by index (no branch); only
the extra functions (cos, sin, abs, min, max) branch. Indices are uint32,
which spares numba's negative-index wraparound. Measured (P = 250 × 3 trees
of 40 nodes, 2 cores under load 8–9, best per call): 153 µs for the prefix
stack machine this replaced, 69 µs with one instruction per function, 46 µs
with the trees interleaved, 37 µs with uint32 indices.

`evaluate` runs individuals in parallel; `evaluate_serial` runs the whole
stream on one thread. Both do the same floating-point operations on the same
operands (order does not change a pure function's value), so they agree bit
for bit with each other and with the numpy reference in
`sinews.control.gp.interpreter` (semantics: `sinews.control.gp.primitives`).

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
    ARITY,
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

__all__ = ["evaluate", "evaluate_serial", "translate"]

IntArray = npt.NDArray[np.int32]
CodeArray = npt.NDArray[np.uint32]
IndexArray = npt.NDArray[np.int64]
FloatArray = npt.NDArray[np.float64]


@njit(cache=True)
def translate(
    code: IntArray,
    tree_start: IndexArray,
    const_start: IndexArray,
    n_trees: int,
    n_inputs: int,
) -> tuple[CodeArray, IndexArray, IndexArray, int]:
    """The register-machine form of packed trees.

    Args:
        code: (N,) packed node codes.
        tree_start: (P·J + 1,) first node of each tree, then N.
        const_start: (P·J + 1,) first constant of each tree, then C.
        n_trees: J.
        n_inputs: V, input slots per individual (more than the highest terminal read).

    Returns:
        ``(instructions, first, result, n_slots)``: (F, 5) uint32 rows
        ``(op, a, b, c, dst)`` (unused operands repeat ``a``); (P + 1,) first
        instruction of each individual, then F; (P·J,) slot of each tree's
        value; S.
    """
    n_all = len(tree_start) - 1
    n_functions = 0
    height = 0  # the tallest stack any tree needs
    for t in range(n_all):
        h = 0
        for i in range(tree_start[t + 1] - 1, tree_start[t] - 1, -1):
            op = code[i]
            if op >= CONST:
                h += 1
                height = max(height, h)
            else:
                n_functions += 1
                h -= ARITY[op] - 1
    const_base = n_all // n_trees * n_inputs
    temp_base = const_base + const_start[-1]
    postfix = np.empty((n_functions, 5), dtype=np.uint32)  # tree by tree
    tree_first = np.zeros(n_all + 1, dtype=np.int64)
    result = np.empty(n_all, dtype=np.int64)
    stack = np.empty(height, dtype=np.int64)  # slots of the values not yet consumed
    n = 0
    for t in range(n_all):
        c = const_start[t + 1]
        top = 0
        for i in range(tree_start[t + 1] - 1, tree_start[t] - 1, -1):
            op = code[i]
            if op >= VAR:
                stack[top] = t // n_trees * n_inputs + op - VAR
            elif op == CONST:
                c -= 1
                stack[top] = const_base + c
            else:
                k = ARITY[op]
                a = stack[top - 1]  # the first argument is the last pushed
                postfix[n, 0] = op
                postfix[n, 1] = a
                postfix[n, 2] = stack[top - 2] if k > 1 else a
                postfix[n, 3] = stack[top - 3] if k > 2 else a
                top -= k
                stack[top] = temp_base + t * height + top
                postfix[n, 4] = stack[top]
                n += 1
            top += 1
        result[t] = stack[0]
        tree_first[t + 1] = n
    # deal each individual's trees out round robin: independent chains side by side
    instructions = np.empty_like(postfix)
    first = tree_first[::n_trees].copy()
    next_of = tree_first[:-1].copy()
    n = 0
    for t0 in range(0, n_all, n_trees):
        while n < tree_first[t0 + n_trees]:
            for t in range(t0, t0 + n_trees):
                if next_of[t] < tree_first[t + 1]:
                    instructions[n] = postfix[next_of[t]]
                    next_of[t] += 1
                    n += 1
    return instructions, first, result, temp_base + n_all * height


@njit(cache=True, error_model="numpy")
def _execute(
    instructions: CodeArray, start: int, stop: int, slots: FloatArray, choice: FloatArray
) -> None:
    """Run ``instructions[start:stop]`` on ``slots``; ``choice`` is (5,) scratch."""
    for i in range(start, stop):
        op = instructions[i, 0]
        a = slots[instructions[i, 1]]
        b = slots[instructions[i, 2]]
        if op <= IFLTZ:  # the opcode is random: pick from all five, no branch to mispredict
            c = slots[instructions[i, 3]]  # loaded unconditionally, so ifltz is a select
            choice[ADD] = a + b
            choice[SUB] = a - b
            choice[MUL] = a * b
            choice[DIV] = 1.0 if abs(b) < DIVISION_EPSILON else a / b
            choice[IFLTZ] = b if a < 0.0 else c
            r = choice[op]
        elif op == COS:
            r = math.cos(a)
        elif op == SIN:
            r = math.sin(a)
        elif op == ABS:
            r = abs(a)
        elif op == MIN:
            r = a if a < b else b
        else:  # MAX
            r = a if a > b else b
        slots[instructions[i, 4]] = r


@njit(parallel=True, cache=True, error_model="numpy")
def evaluate(
    instructions: CodeArray,
    first: IndexArray,
    result: IndexArray,
    inputs: FloatArray,
    slots: FloatArray,
    out: FloatArray,
) -> None:
    """Fill ``out`` (P, J) with every tree's value on its individual's (V,) row of ``inputs``.

    Args:
        instructions, first, result: from `translate`.
        inputs: (P, V) terminal values, V as given to `translate`.
        slots: (S,) scratch holding the constants (see the module docstring).
        out: (P, J) destination.
    """
    n_programs, n_inputs = inputs.shape
    n_trees = out.shape[1]
    for p in prange(n_programs):
        slots[p * n_inputs : (p + 1) * n_inputs] = inputs[p]
        _execute(instructions, first[p], first[p + 1], slots, np.empty(5))
        for j in range(n_trees):
            out[p, j] = slots[result[p * n_trees + j]]


@njit(cache=True, error_model="numpy")
def evaluate_serial(
    instructions: CodeArray,
    first: IndexArray,
    result: IndexArray,
    inputs: FloatArray,
    slots: FloatArray,
    out: FloatArray,
) -> None:
    """`evaluate` on one thread (same arguments, same results)."""
    n_programs, n_inputs = inputs.shape
    n_trees = out.shape[1]
    for p in range(n_programs):
        slots[p * n_inputs : (p + 1) * n_inputs] = inputs[p]
    _execute(instructions, 0, int(first[n_programs]), slots, np.empty(5))
    for p in range(n_programs):
        for j in range(n_trees):
            out[p, j] = slots[result[p * n_trees + j]]
