"""The numba population interpreter against the numpy reference; protected maths; clamping."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gp_helpers import TERMINALS, make_pset, population, seeds
from sinews.control.gp import (
    GPController,
    GPError,
    PackedPopulation,
    Wiring,
    parse_program,
    parse_tree,
    reference_population,
    reference_tree,
)
from sinews.control.gp.kernels import evaluate, evaluate_serial


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
    p = PackedPopulation.pack(programs)
    args = (p.code, p.consts, p.tree_start, p.const_start, inputs)
    parallel, serial = np.empty((64, 2)), np.empty((64, 2))
    evaluate(*args, parallel, np.empty((64, 400)))
    evaluate_serial(*args, serial, np.empty((64, 400)))
    assert _same(parallel, serial)


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
