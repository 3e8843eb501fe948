"""Trees and programs: structure, depth, slicing, S-expressions and the genome codec."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings

from gp_helpers import TERMINALS, make_pset, population, seeds
from sinews.control.gp import (
    GPError,
    PrimitiveSet,
    Tree,
    decode_program,
    encode_program,
    format_program,
    format_tree,
    parse_program,
    parse_tree,
    program_depth,
    program_size,
)
from sinews.control.gp.primitives import CONST, VAR

FIGURE_7 = """(list
(- (ifltz a0 pz a2) (% a1 t))
(ifltz (- (- (ifltz a0 pz a2) (% a1 t)) (ifltz (+ a2 15.4963) (ifltz a0 pz a2) (% a1 a2))) \
(ifltz (% (- s0 vx) (+ a2 s0)) (% (- s0 vx) (+ a2 s0)) (+ (- a1 a1) (- a1 t))) \
(% (+ a1 vz) (ifltz (* pz a1) (% a0 pz) (% px a0))))
(- (ifltz s0 (ifltz (- (% vx a0) (% vx vx)) (- (% vx a0) (- (+ -28.4382 t) (% a1 t))) \
(* 16.5266 s0)) vz) (+ a1 vz)))"""

PAPER = PrimitiveSet(("a0", "a1", "a2", "s0", "px", "pz", "vx", "vz", "t"))


def test_the_papers_figure_7_program_parses_and_prints_back_verbatim() -> None:
    program = parse_program(FIGURE_7, PAPER)
    assert len(program) == 3
    assert [len(tree) for tree in program] == [8, 57, 29]
    assert [tree.depth for tree in program] == [2, 4, 6]
    assert program[2].consts.tolist() == [-28.4382, 16.5266]
    assert format_program(program, PAPER) == FIGURE_7


@settings(max_examples=30, deadline=None)
@given(seed=seeds)
def test_print_then_parse_gives_the_same_program(seed: int) -> None:
    pset = make_pset(extras=True)
    for program in population(seed, 12, extras=True):
        text = format_program(program, pset)
        assert parse_program(text, pset) == program
        assert decode_program(encode_program(program, pset), pset) == program
        for tree in program:
            assert parse_tree(format_tree(tree, pset), pset) == tree


def test_a_tree_is_checked_when_made() -> None:
    x = VAR + TERMINALS.index("gx")
    Tree(np.array([0, x, CONST]), np.array([1.5]))  # (+ gx 1.5)
    for code, consts in [
        ([0, x], []),  # an argument missing
        ([0, x, x, x], []),  # one too many
        ([x, CONST], [2.0]),  # two roots
        ([0, x, CONST], []),  # a constant without a value
        ([0, x, CONST], [np.nan]),
        ([], []),
    ]:
        with pytest.raises(GPError):
            Tree(np.array(code, dtype=np.int32), np.array(consts))


def test_depth_end_subtree_and_replace() -> None:
    pset = make_pset()
    tree = parse_tree("(+ (* gx 2.0) (ifltz time q_a (- q_b 3.0)))", pset)
    assert tree.depth == 3
    assert tree.node_depths.tolist() == [0, 1, 2, 2, 1, 2, 2, 2, 3, 3]
    assert tree.end(0) == len(tree)
    assert format_tree(tree.subtree(1), pset) == "(* gx 2.0)"
    assert format_tree(tree.subtree(7), pset) == "(- q_b 3.0)"
    swapped = tree.replace(1, parse_tree("(% 5.0 q_a)", pset))
    assert format_tree(swapped, pset) == "(+ (% 5.0 q_a) (ifltz time q_a (- q_b 3.0)))"
    assert swapped.consts.tolist() == [5.0, 3.0]
    program = (tree, swapped.subtree(1))
    assert program_depth(program) == 3 and program_size(program) == 10
    with pytest.raises(GPError):
        tree.end(10)


def test_trees_are_values() -> None:
    pset = make_pset()
    a, b = parse_tree("(+ gx 1.0)", pset), parse_tree("(+ gx 1.0)", pset)
    assert a == b and hash(a) == hash(b) and a != parse_tree("(+ gx 1.5)", pset)
    with pytest.raises(ValueError):
        a.code[0] = 1


@pytest.mark.parametrize(
    "text",
    [
        "(list (+ gx))",
        "(list (+ gx q_a q_b))",
        "(list)",
        "(+ gx q_a)",
        "(list (+ gx q_a)",
        "(list + gx)",
        "(list (foo gx))",
        "(list unknown)",
        "(list (cos gx))",  # not in this primitive set
        "(list (+ gx q_a)))",
    ],
)
def test_bad_text_is_refused_with_a_gp_error(text: str) -> None:
    with pytest.raises(GPError):
        parse_program(text, make_pset())


def test_primitive_sets_refuse_bad_names_and_round_trip() -> None:
    for terminals in (("x", "x"), ("1.5",), ("list",), ("ifltz",), ("a b",), ("",)):
        with pytest.raises(GPError):
            PrimitiveSet(terminals)
    with pytest.raises(GPError):
        PrimitiveSet(("x",), functions=("tan",))
    with pytest.raises(GPError):
        PrimitiveSet(("x",), erc_range=(1.0, 1.0))
    with pytest.raises(GPError):
        decode_program(b"\xff", make_pset())
    pset = make_pset(extras=True)
    assert PrimitiveSet.from_dict(pset.to_dict()) == pset
