"""Making and varying programs: ramped half-and-half, subtree crossover and mutation, limits.

Every random choice is drawn from the generator passed in, in a fixed order,
so the same generator state gives the same programs.

Koza's choices (the paper follows his book): initial trees of depth 2 to 6,
half grown and half full; crossover points are function nodes 90% of the
time; children deeper than 17 are not allowed. `tweak_constants` is not the
paper's: a Gaussian nudge of one tree's constants, which subtree operators
can only replace wholesale. Every tree made here is
within the `Limits`: random trees respect a size budget as well as a depth
(a full tree of depth 6 over ``ifltz`` would otherwise have 1093 nodes), and
a crossover or mutation whose child would break a limit is drawn again at
other points (`within_limits`), never replaced by a copy of its parent
(DEAP's ``staticLimit``), which let one early program copy itself over a
whole population.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from sinews.control.gp.primitives import ARITY, CONST, VAR, GPError, PrimitiveSet
from sinews.control.gp.tree import Program, Tree, program_depth, program_size

__all__ = [
    "WITHIN_LIMITS_TRIES",
    "Limits",
    "crossover",
    "leaf_crossover",
    "mutate",
    "pick_point",
    "ramped_half_and_half",
    "random_tree",
    "tweak_constants",
    "within_limits",
]

INTERNAL_PROBABILITY = 0.9
"""Koza's chance that a crossover or mutation point is a function node."""


@dataclass(frozen=True)
class Limits:
    """Bloat limits on every tree of a program (the list root is not counted).

    Attributes:
        max_depth: deepest allowed tree (a lone terminal has depth 0).
        max_size: most nodes allowed in one tree.
    """

    max_depth: int = 17
    max_size: int = 200

    def __post_init__(self) -> None:
        if self.max_depth < 1 or self.max_size < 3:
            raise GPError("limits need max_depth >= 1 and max_size >= 3")

    def admits(self, program: Program) -> bool:
        """True if every tree is within both limits."""
        return program_size(program) <= self.max_size and program_depth(program) <= self.max_depth


def random_tree(
    pset: PrimitiveSet,
    rng: np.random.Generator,
    depth: int,
    *,
    full: bool,
    max_size: int | None = None,
) -> Tree:
    """A random tree of at most ``depth`` (exactly ``depth`` if ``full`` and size allows).

    The root is a function (when ``depth`` > 0). Below it, "full" places
    functions down to ``depth``; "grow" picks uniformly among the functions
    and the terminals (all named terminals plus one for a random constant).
    The nodes at ``depth`` are terminals. With ``max_size``, a function is
    placed only if the tree, with a terminal for every open argument, still
    fits: functions of too many arguments are left out of the draw, and a
    node where none fits is a terminal.

    Args:
        pset: the primitives.
        rng: the generator.
        depth: the depth limit (>= 0).
        full: "full" (True) or "grow" (False).
        max_size: the most nodes the tree may have (>= 1), or None.
    """
    codes: list[int] = []
    consts: list[float] = []
    slots = [0]  # depths of the nodes still to place, the next one last
    n_leaves = pset.n_terminals + 1
    all_functions = pset.function_codes
    while slots:
        level = slots.pop()
        functions = all_functions
        if max_size is not None:  # placed + still open + this node's new arguments must fit
            room = max_size - len(codes) - len(slots) - 1
            functions = all_functions[ARITY[all_functions] <= room]
        n_functions = len(functions)
        if level < depth and n_functions and (full or level == 0):
            pick = int(rng.integers(n_functions))
        elif level < depth and n_functions:
            pick = int(rng.integers(n_functions + n_leaves))
        else:
            pick = n_functions + int(rng.integers(n_leaves))
        if pick < n_functions:
            code = int(functions[pick])
            codes.append(code)
            slots.extend([level + 1] * int(ARITY[code]))
        elif pick - n_functions == pset.n_terminals:
            codes.append(CONST)
            consts.append(float(pset.erc(rng)))
        else:
            codes.append(VAR + pick - n_functions)
    return Tree(np.array(codes), np.array(consts))


def ramped_half_and_half(
    pset: PrimitiveSet,
    rng: np.random.Generator,
    *,
    n_programs: int,
    n_trees: int,
    min_depth: int = 2,
    max_depth: int = 6,
    retries: int = 20,
    max_size: int | None = None,
) -> list[Program]:
    """Koza's initial population: depths ramped over the programs, half full, half grown.

    Program ``i`` gets depth ``min_depth + i mod (max_depth - min_depth + 1)``
    and is full on even passes over the depths, grown on odd ones; all its
    trees share that depth and method, and have at most ``max_size`` nodes
    (see `random_tree`). A program equal to an earlier one is drawn again (up
    to ``retries`` times), so the population starts diverse.

    Returns:
        ``n_programs`` programs of ``n_trees`` trees each.
    """
    if not 0 <= min_depth <= max_depth or n_programs < 0 or n_trees < 1:
        raise GPError("need 0 <= min_depth <= max_depth, n_programs >= 0 and n_trees >= 1")
    n_depths = max_depth - min_depth + 1
    seen: set[Program] = set()
    programs: list[Program] = []
    for i in range(n_programs):
        depth, full = min_depth + i % n_depths, (i // n_depths) % 2 == 0
        for _ in range(retries + 1):
            program = tuple(
                random_tree(pset, rng, depth, full=full, max_size=max_size) for _ in range(n_trees)
            )
            if program not in seen:
                break
        seen.add(program)
        programs.append(program)
    return programs


def pick_point(tree: Tree, rng: np.random.Generator) -> int:
    """A node of ``tree``: a function node with probability 0.9 (if any), else a leaf."""
    internal = tree.internal
    if len(internal) and rng.random() < INTERNAL_PROBABILITY:
        return int(internal[rng.integers(len(internal))])
    leaves = tree.leaves
    return int(leaves[rng.integers(len(leaves))])


def crossover(
    a: Program, b: Program, rng: np.random.Generator, *, any_slot: bool = False
) -> tuple[Program, Program]:
    """Swap a random subtree of one of ``a``'s trees with one of ``b``'s.

    By default both subtrees come from the same slot (the same joint's tree),
    as the paper's list-rooted programs imply; with ``any_slot`` the slots
    are drawn independently. The list root and the number of trees never change.

    Returns:
        The child that is ``a`` with ``b``'s subtree, and the one that is
        ``b`` with ``a``'s.
    """
    if len(a) != len(b):
        raise GPError("crossover needs programs with the same number of trees")
    slot_a = int(rng.integers(len(a)))
    slot_b = int(rng.integers(len(b))) if any_slot else slot_a
    tree_a, tree_b = a[slot_a], b[slot_b]
    i, j = pick_point(tree_a, rng), pick_point(tree_b, rng)
    child_a = tree_a.replace(i, tree_b.subtree(j))
    child_b = tree_b.replace(j, tree_a.subtree(i))
    return _with(a, slot_a, child_a), _with(b, slot_b, child_b)


def mutate(
    program: Program,
    pset: PrimitiveSet,
    rng: np.random.Generator,
    *,
    depth: int = 4,
    limits: Limits | None = None,
) -> Program:
    """Replace a random subtree of a random tree with a new grown tree of depth <= ``depth``.

    With ``limits``, the new subtree is sized so the tree stays within
    ``max_size`` (the depth is checked by the caller).
    """
    slot = int(rng.integers(len(program)))
    tree = program[slot]
    point = pick_point(tree, rng)
    budget = None
    if limits is not None:
        budget = max(1, limits.max_size - len(tree) + len(tree.subtree(point)))
    new = random_tree(pset, rng, depth, full=False, max_size=budget)
    return _with(program, slot, tree.replace(point, new))


def tweak_constants(
    program: Program, pset: PrimitiveSet, rng: np.random.Generator, *, scale: float
) -> Program:
    """Add Gaussian noise to every constant of one random tree that has constants.

    The noise's standard deviation is ``scale`` times the width of the ERC range;
    the results are rounded as ERCs are (``pset.erc_decimals``). A program
    without constants comes back unchanged. The tree's shape never changes, so
    the child is within any limits its parent is.
    """
    with_consts = [k for k, tree in enumerate(program) if tree.consts.size]
    if not with_consts:
        return program
    slot = with_consts[int(rng.integers(len(with_consts)))]
    tree = program[slot]
    lo, hi = pset.erc_range
    consts = tree.consts + rng.normal(0.0, scale * (hi - lo), size=tree.consts.size)
    if pset.erc_decimals is not None:
        consts = np.round(consts, pset.erc_decimals)
    return _with(program, slot, Tree(tree.code, consts))


WITHIN_LIMITS_TRIES = 20
"""Draws of a variation before `within_limits` falls back to swapping terminals."""


def within_limits(
    vary: Callable[[], Program], fallback: Callable[[], Program], limits: Limits
) -> Program:
    """The first of up to `WITHIN_LIMITS_TRIES` draws of ``vary()`` that is within ``limits``.

    If none is, ``fallback()``: a variation that cannot grow a tree (such as
    `leaf_crossover`), so from parents within the limits it always fits.
    """
    for _ in range(WITHIN_LIMITS_TRIES):
        child = vary()
        if limits.admits(child):
            return child
    return fallback()


def leaf_crossover(a: Program, b: Program, rng: np.random.Generator) -> Program:
    """``a`` with one terminal replaced by one of ``b``'s (same slot): never grows a tree."""
    slot = int(rng.integers(len(a)))
    tree_a, tree_b = a[slot], b[slot]
    i, j = int(rng.choice(tree_a.leaves)), int(rng.choice(tree_b.leaves))
    return _with(a, slot, tree_a.replace(i, tree_b.subtree(j)))


def _with(program: Program, slot: int, tree: Tree) -> Program:
    return (*program[:slot], tree, *program[slot + 1 :])
