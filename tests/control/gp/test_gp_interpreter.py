"""The numba population interpreter against the numpy reference; protected maths; clamping."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gp_helpers import TERMINALS, make_pset, population, seeds
from sinews.control.gp import (
    FUNCTIONS,
    GPController,
    GPError,
    PackedPopulation,
    Wiring,
    parse_program,
    parse_tree,
    reference_population,
    reference_tree,
)
from sinews.control.gp.primitives import CONST, VAR
from sinews.control.gp.tree import Tree


def _inputs(seed: int, n: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    values = rng.normal(0.0, 3.0, (n, len(TERMINALS)))
    special = rng.random(values.shape)
    values[special < 0.1] = 0.0  # divisions by zero and ifltz at 0
    values[special > 0.97] = rng.choice(
        [np.inf, -np.inf, np.nan, 1e-12, 1e300], size=(special > 0.97).sum()
    )
    return values


def _same(a: np.ndarray, b: np.ndarray) -> bool:
    return bool(np.array_equal(a, b, equal_nan=True))


@settings(max_examples=30, deadline=None)
@given(seed=seeds, extras=st.booleans(), n=st.integers(1, 40))
def test_the_interpreter_matches_the_reference_bit_for_bit(seed: int, extras: bool, n: int) -> None:
    programs = population(seed, n, n_trees=3, extras=extras)
    inputs = _inputs(seed, n)
    packed = PackedPopulation.pack(programs)
    assert _same(packed.evaluate(inputs), reference_population(programs, inputs))


@settings(max_examples=10, deadline=None)
@given(seed=seeds)
def test_parallel_and_serial_kernels_agree(seed: int) -> None:
    programs = population(seed, 64, n_trees=2, extras=True)
    inputs = _inputs(seed, 64)
    packed = PackedPopulation.pack(programs)
    parallel = packed.evaluate(inputs, parallel=True)
    assert _same(parallel, packed.evaluate(inputs))
    assert _same(parallel, reference_population(programs, inputs))


@pytest.mark.parametrize(
    ("text", "row", "expected"),
    [
        ("(% gx q_a)", [0, 3.0, 0.0, 0], 1.0),  # protected division
        ("(% gx q_a)", [0, 3.0, 1e-12, 0], 1.0),  # ~0 counts as 0
        ("(% gx q_a)", [0, 3.0, 2.0, 0], 1.5),
        ("(% gx q_a)", [0, 3.0, -2.0, 0], -1.5),
        ("(ifltz gx 1.0 2.0)", [0, -0.5, 0, 0], 1.0),
        ("(ifltz gx 1.0 2.0)", [0, 0.0, 0, 0], 2.0),
        ("(ifltz gx 1.0 2.0)", [0, np.nan, 0, 0], 2.0),
        ("(- gx q_a)", [0, 1.0, 4.0, 0], -3.0),  # first argument first
        ("(min gx q_a)", [0, 1.0, 4.0, 0], 1.0),
        ("(max gx q_a)", [0, 1.0, 4.0, 0], 4.0),
        ("(abs (cos (* 0.0 time)))", [7.0, 0, 0, 0], 1.0),
        ("(* gx q_a)", [0, 1e200, 1e200, 0], np.inf),
    ],
)
def test_primitive_semantics(text: str, row: list[float], expected: float) -> None:
    pset = make_pset(extras=True)
    inputs = np.array([row])
    tree = parse_tree(text, pset)
    assert reference_tree(tree, inputs)[0] == expected
    assert PackedPopulation.pack([(tree,)]).evaluate(inputs)[0, 0] == expected


def _wiring(n_trees: int = 2) -> Wiring:
    """Terminals = the 4 sensor columns, trees drive actuators 2 and 0 of 3."""
    return Wiring(
        input_weights=np.eye(4),
        input_offset=np.zeros(4),
        actuators=np.array([2, 0][:n_trees]),
        neutral=np.array([0.1, 0.2, 0.3]),
        joint_range=np.array([[-1.0, 1.0], [-2.0, 2.0], [-0.5, 0.5]]),
    )


def test_the_controller_clips_clamps_and_counts_nonfinite_values() -> None:
    pset = make_pset()
    programs = [
        parse_program("(list (* gx 10.0) gx)", pset),  # finite: clipped to the range
        parse_program("(list (* gx gx) (- (* gx gx) (* gx gx)))", pset),  # inf, then NaN
    ]
    controller = GPController(programs, _wiring())
    controller.reset(2)
    sensors = np.array([[0.0, 0.2, 0.0, 0.0], [0.0, 1e200, 0.0, 0.0]])
    targets = controller.control(0.0, sensors)
    np.testing.assert_array_equal(targets[0], [0.2, 0.2, 0.5])  # untouched joint 1 is neutral
    np.testing.assert_array_equal(targets[1], [0.1, 0.2, 0.5])  # NaN → neutral, inf → the top
    assert controller.nonfinite.tolist() == [0, 2]
    controller.control(0.01, sensors)
    assert controller.nonfinite.tolist() == [0, 4]
    controller.reset(2)
    assert controller.nonfinite.tolist() == [0, 0]


def test_the_controller_and_packer_refuse_mismatches() -> None:
    pset = make_pset()
    program = parse_program("(list gx gx)", pset)
    with pytest.raises(GPError):
        GPController([program], _wiring(n_trees=1))
    controller = GPController([program], _wiring())
    with pytest.raises(GPError):
        controller.reset(3)
    with pytest.raises(GPError):
        PackedPopulation.pack([program, parse_program("(list gx)", pset)])
    with pytest.raises(GPError):
        PackedPopulation.pack([parse_program("(list q_b)", pset)]).evaluate(np.zeros((1, 2)))
    with pytest.raises(GPError):
        Wiring(np.eye(4), np.zeros(3), np.array([0]), np.zeros(3), np.zeros((3, 2)))
    with pytest.raises(GPError):
        Wiring(np.eye(4), np.zeros(4), np.array([0, 0]), np.zeros(3), np.zeros((3, 2)))


_SPECIAL_CONSTANTS = (0.0, -0.0, 1e-12, -1e-10, 1e300, -1e300, 3.5)


def _random_tree(rng: np.random.Generator, pset_functions: tuple[str, ...]) -> Tree:
    """One tree of a random shape: a lone leaf, a bushy tree, or a deep chain."""
    functions = [FUNCTIONS[f] for f in pset_functions]
    codes: list[int] = []
    consts: list[float] = []

    def leaf() -> None:
        if rng.random() < 0.4:
            codes.append(CONST)
            special = rng.random() < 0.3
            consts.append(float(rng.choice(_SPECIAL_CONSTANTS)) if special else rng.normal())
        else:
            codes.append(VAR + int(rng.integers(len(TERMINALS))))

    def grow(depth: int, p_leaf: float) -> None:
        if depth == 0 or rng.random() < p_leaf:
            leaf()
            return
        code, arity = functions[rng.integers(len(functions))]
        codes.append(code)
        for _ in range(arity):
            grow(depth - 1, p_leaf)

    def chain(length: int, first_argument_deep: bool) -> None:
        """``length`` functions nested through one argument (a tall or a flat stack)."""
        if length == 0:
            leaf()
            return
        code, arity = functions[rng.integers(len(functions))]
        codes.append(code)
        deep = 0 if first_argument_deep else arity - 1
        for k in range(arity):
            chain(length - 1, first_argument_deep) if k == deep else leaf()

    shape = rng.integers(4)
    if shape == 0:
        leaf()
    elif shape == 1:
        grow(int(rng.integers(1, 12)), float(rng.uniform(0.1, 0.7)))
    else:
        chain(int(rng.integers(1, 120)), first_argument_deep=shape == 2)
    return Tree(np.array(codes), np.array(consts))


@settings(max_examples=25, deadline=None)
@given(seed=seeds, extras=st.booleans(), n=st.integers(1, 12), n_trees=st.integers(1, 4))
def test_odd_shapes_match_the_reference_on_every_kernel(
    seed: int, extras: bool, n: int, n_trees: int
) -> None:
    """Lone leaves, bushy trees, deep chains through the first or the last argument
    (tall and flat stacks), special constants and inputs: every kernel, bit for bit."""
    rng = np.random.default_rng(seed)
    functions = make_pset(extras).functions
    programs = [tuple(_random_tree(rng, functions) for _ in range(n_trees)) for _ in range(n)]
    inputs = _inputs(seed, n)
    packed = PackedPopulation.pack(programs)
    expected = reference_population(programs, inputs)
    assert _same(packed.evaluate(inputs), expected)
    assert _same(packed.evaluate(inputs, parallel=True), expected)
    assert _same(packed.evaluate(inputs), expected)  # the slots are scratch: a second call agrees
