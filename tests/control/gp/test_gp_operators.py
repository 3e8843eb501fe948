"""GP operators, property-tested: trees stay well-typed and within limits, the list root intact."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from gp_helpers import make_pset, population, seeds
from sinews.control.gp import (
    Limits,
    PrimitiveSet,
    Program,
    crossover,
    mutate,
    parse_tree,
    pick_point,
    program_depth,
    ramped_half_and_half,
    random_tree,
    tweak_constants,
)
from sinews.control.gp.primitives import ARITY, CONST


def _assert_well_typed(program: Program, n_trees: int) -> None:
    """One tree per slot, every node a primitive of the set with its arity's arguments."""
    pset = make_pset(extras=True)
    assert isinstance(program, tuple) and len(program) == n_trees
    for tree in program:
        pset.check(tree.code)
        # every function node's subtree is contiguous and closes inside the tree
        for i in tree.internal.tolist():
            assert i < tree.end(i) <= len(tree)
            children, at = 0, i + 1
            while at < tree.end(i):
                at = tree.end(at)
                children += 1
            assert children == ARITY[tree.code[i]]
        assert len(tree.consts) == np.count_nonzero(tree.code == CONST)


@settings(max_examples=25, deadline=None)
@given(seed=seeds, depth=st.integers(0, 7), full=st.booleans())
def test_random_trees_respect_their_depth(seed: int, depth: int, full: bool) -> None:
    pset = make_pset(extras=True)
    tree = random_tree(pset, np.random.default_rng(seed), depth, full=full)
    _assert_well_typed((tree,), 1)
    if full:
        assert tree.depth == depth
        leaves = tree.node_depths[tree.code >= CONST]
        assert (leaves == depth).all()
    else:
        assert tree.depth <= depth
    if depth:
        assert tree.code[0] < CONST  # the root is a function


@settings(max_examples=10, deadline=None)
@given(seed=seeds)
def test_ramped_half_and_half_ramps_depths_and_is_duplicate_free(seed: int) -> None:
    pset = make_pset()
    rng = np.random.default_rng(seed)
    programs = ramped_half_and_half(pset, rng, n_programs=24, n_trees=3, min_depth=1, max_depth=4)
    assert len(programs) == 24 and len(set(programs)) == 24
    for i, program in enumerate(programs):
        _assert_well_typed(program, 3)
        depth = 1 + i % 4
        assert program_depth(program) <= depth
        if (i // 4) % 2 == 0:  # full
            assert all(tree.depth == depth for tree in program)


@settings(max_examples=40, deadline=None)
@given(seed=seeds, any_slot=st.booleans())
def test_crossover_swaps_subtrees_and_keeps_the_list_root(seed: int, any_slot: bool) -> None:
    rng = np.random.default_rng(seed)
    a, b = population(seed, 2, n_trees=3, extras=True)
    child_a, child_b = crossover(a, b, rng, any_slot=any_slot)
    _assert_well_typed(child_a, 3)
    _assert_well_typed(child_b, 3)
    changed_a = [k for k in range(3) if child_a[k] != a[k]]
    changed_b = [k for k in range(3) if child_b[k] != b[k]]
    assert len(changed_a) <= 1 and len(changed_b) <= 1
    if not any_slot and changed_a and changed_b:
        assert changed_a == changed_b
    # material is conserved: together the children hold the parents' nodes
    nodes = sum(len(t) for t in a + b)
    assert sum(len(t) for t in child_a + child_b) == nodes
    consts = sorted(np.concatenate([t.consts for t in a + b]).tolist())
    assert sorted(np.concatenate([t.consts for t in child_a + child_b]).tolist()) == consts


@settings(max_examples=25, deadline=None)
@given(seed=seeds)
def test_mutation_changes_one_tree_and_stays_well_typed(seed: int) -> None:
    pset = make_pset(extras=True)
    rng = np.random.default_rng(seed)
    (program,) = population(seed, 1, n_trees=4, extras=True)
    child = mutate(program, pset, rng, depth=3)
    _assert_well_typed(child, 4)
    assert sum(child[k] != program[k] for k in range(4)) <= 1


@settings(max_examples=25, deadline=None)
@given(seed=seeds)
def test_a_tweak_nudges_one_trees_constants_and_keeps_its_shape(seed: int) -> None:
    pset = make_pset(extras=True)
    (program,) = population(seed, 1, n_trees=4, extras=True)
    child = tweak_constants(program, pset, np.random.default_rng(seed), scale=0.05)
    assert child == tweak_constants(program, pset, np.random.default_rng(seed), scale=0.05)
    _assert_well_typed(child, 4)
    changed = [k for k in range(4) if child[k] != program[k]]
    if not any(tree.consts.size for tree in program):
        assert child is program
        return
    assert len(changed) <= 1  # exactly one unless every nudge rounded to nothing
    for k in changed:
        np.testing.assert_array_equal(child[k].code, program[k].code)
        step = child[k].consts - program[k].consts
        assert np.abs(step).max() < 10 * 0.05 * 10.0  # 10 sigma of 5 % of the range (-5, 5)
        np.testing.assert_array_equal(child[k].consts, np.round(child[k].consts, 4))


def test_a_tweak_without_rounding_moves_every_constant_of_the_tree() -> None:
    pset = PrimitiveSet(("time",), erc_range=(-1.0, 1.0), erc_decimals=None)
    tree = parse_tree("(+ 0.5 (* time -0.25))", pset)
    (child,) = tweak_constants((tree,), pset, np.random.default_rng(1), scale=0.01)
    np.testing.assert_array_equal(child.code, tree.code)
    assert (child.consts != tree.consts).all()
    assert np.abs(child.consts - tree.consts).max() < 0.1
    bare = (parse_tree("(+ time time)", pset),)
    assert tweak_constants(bare, pset, np.random.default_rng(1), scale=0.01) is bare


@settings(max_examples=25, deadline=None)
@given(seed=seeds)
def test_crossover_points_are_mostly_functions(seed: int) -> None:
    rng = np.random.default_rng(seed)
    (program,) = population(seed, 1, n_trees=1)
    tree = program[0]
    points = [pick_point(tree, rng) for _ in range(200)]
    internal = np.isin(points, tree.internal).mean()
    assert (internal > 0.75) if len(tree.internal) else internal == 0.0


def test_limits_check_every_tree() -> None:
    pset = make_pset()
    rng = np.random.default_rng(0)
    deep = random_tree(pset, rng, 6, full=True)
    small = random_tree(pset, rng, 1, full=True)
    assert Limits(max_depth=6, max_size=10_000).admits((small, deep))
    assert not Limits(max_depth=5, max_size=10_000).admits((small, deep))
    assert not Limits(max_depth=17, max_size=len(deep) - 1).admits((deep, small))
