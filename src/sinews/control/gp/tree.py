"""Expression trees as flat arrays in prefix order, and programs as one tree per joint.

A `Tree` is its node codes in prefix order (see `sinews.control.gp.primitives`)
plus its constant pool: the values of its ``CONST`` nodes, in the same prefix
order. The subtree rooted at node ``i`` is the contiguous slice ``[i,
tree.end(i))`` of the codes (DEAP's idea: prefix order with arities) and a
contiguous slice of the pool, so crossover is slicing and concatenation.

A `Program` is the paper's ``(list t1 t2 ...)``: one tree per controlled joint,
whose value is that joint's desired angle. The list root is not a node of any
tree, so no operator can break it.

The depth of a lone terminal is 0 (as in DEAP and Koza); a program's depth and
size are those of its deepest and largest tree.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
import numpy.typing as npt

from sinews.control.gp.primitives import CONST, GPError, arities

__all__ = ["Program", "Tree", "program_depth", "program_size"]

IntArray = npt.NDArray[np.int32]
FloatArray = npt.NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class Tree:
    """One expression: node codes in prefix order and their constants.

    Attributes:
        code: (n,) int32 node codes, prefix order (read-only).
        consts: (c,) float64 values of the ``CONST`` nodes, prefix order (read-only).

    Raises:
        GPError: the codes are not exactly one well-formed prefix expression,
            or the pool does not match the constant nodes.
    """

    code: IntArray
    consts: FloatArray

    def __post_init__(self) -> None:
        code = np.array(self.code, dtype=np.int32).reshape(-1)
        consts = np.array(self.consts, dtype=np.float64).reshape(-1)
        if code.size == 0 or code.min() < 0:
            raise GPError("a tree needs at least one node and non-negative codes")
        open_slots = 1 + np.cumsum(arities(code) - 1)
        if open_slots[-1] != 0 or (open_slots[:-1] <= 0).any():
            raise GPError("the codes are not one well-formed prefix expression")
        if np.count_nonzero(code == CONST) != consts.size or not np.isfinite(consts).all():
            raise GPError("the constant pool must hold one finite value per constant node")
        code.flags.writeable = False
        consts.flags.writeable = False
        object.__setattr__(self, "code", code)
        object.__setattr__(self, "consts", consts)

    def __len__(self) -> int:
        return int(self.code.size)

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Tree):
            return NotImplemented
        return np.array_equal(self.code, other.code) and np.array_equal(self.consts, other.consts)

    def __hash__(self) -> int:
        return hash((self.code.tobytes(), self.consts.tobytes()))

    @cached_property
    def _arity(self) -> IntArray:
        return arities(self.code)

    @cached_property
    def _consts_before(self) -> npt.NDArray[np.intp]:
        """(n + 1,) number of constant nodes before each node (and in total)."""
        return np.concatenate([[0], np.cumsum(self.code == CONST)])

    @cached_property
    def node_depths(self) -> npt.NDArray[np.intp]:
        """(n,) depth of each node (the root is at 0)."""
        depths = np.empty(len(self), dtype=np.intp)
        open_children: list[int] = []  # per open ancestor: children still to come
        for i, arity in enumerate(self._arity.tolist()):
            depths[i] = len(open_children)
            if open_children:
                open_children[-1] -= 1
            if arity:
                open_children.append(arity)
            while open_children and open_children[-1] == 0:
                open_children.pop()
        depths.flags.writeable = False
        return depths

    @property
    def depth(self) -> int:
        """Depth of the deepest node."""
        return int(self.node_depths.max())

    @property
    def internal(self) -> npt.NDArray[np.intp]:
        """Indices of the function nodes."""
        return np.flatnonzero(self._arity > 0)

    @property
    def leaves(self) -> npt.NDArray[np.intp]:
        """Indices of the terminals (variables and constants)."""
        return np.flatnonzero(self._arity == 0)

    def end(self, i: int) -> int:
        """One past the last node of the subtree rooted at node ``i``."""
        if not 0 <= i < len(self):
            raise GPError(f"node {i} is not in a tree of {len(self)} nodes")
        closed = np.cumsum(self._arity[i:] - 1) == -1
        return i + int(np.argmax(closed)) + 1

    def subtree(self, i: int) -> Tree:
        """The subtree rooted at node ``i``, as a tree of its own."""
        end = self.end(i)
        first, last = self._consts_before[i], self._consts_before[end]
        return Tree(self.code[i:end], self.consts[first:last])

    def replace(self, i: int, subtree: Tree) -> Tree:
        """A copy with the subtree rooted at node ``i`` replaced by ``subtree``."""
        end = self.end(i)
        first, last = self._consts_before[i], self._consts_before[end]
        return Tree(
            np.concatenate([self.code[:i], subtree.code, self.code[end:]]),
            np.concatenate([self.consts[:first], subtree.consts, self.consts[last:]]),
        )


Program = tuple[Tree, ...]
"""One tree per controlled joint: the paper's ``(list ...)`` root with its children."""


def program_depth(program: Program) -> int:
    """Depth of the program's deepest tree."""
    return max(tree.depth for tree in program)


def program_size(program: Program) -> int:
    """Node count of the program's largest tree."""
    return max(len(tree) for tree in program)
