"""Fitness specs: weights, the phase-in schedule, failures, parsing."""

from __future__ import annotations

import numpy as np
import pytest

from sinews.evolve import WORST_FITNESS, FitnessError, FitnessSpec, PhaseIn, parse_weights


def test_phase_in_is_zero_then_linear_then_full() -> None:
    schedule = PhaseIn(start=3, full=6)
    factors = [schedule.factor(g) for g in range(9)]
    assert factors[:3] == [0.0, 0.0, 0.0]
    assert factors[3:6] == pytest.approx([0.25, 0.5, 0.75])
    assert factors[6:] == [1.0, 1.0, 1.0]
    assert PhaseIn().factor(0) == 1.0


def test_phase_in_needs_ordered_generations() -> None:
    with pytest.raises(FitnessError, match="start <= full"):
        PhaseIn(start=5, full=2)


def spec() -> FitnessSpec:
    return FitnessSpec(
        main="goal", weights={"goal": 2.0, "style": 0.5}, phase_in=PhaseIn(start=1, full=2)
    )


def test_main_goal_only_until_style_phases_in() -> None:
    terms = np.array([[1.0, 10.0], [2.0, -4.0]])
    failed = np.zeros(2, dtype=bool)
    np.testing.assert_array_equal(spec().combine(terms, failed, 0), [2.0, 4.0])
    np.testing.assert_allclose(spec().combine(terms, failed, 1), [2.0 + 2.5, 4.0 - 1.0])
    np.testing.assert_allclose(spec().combine(terms, failed, 7), [7.0, 2.0])
    assert spec().weights_at(0) == {"goal": 2.0, "style": 0.0}


def test_failed_or_nan_individuals_get_the_worst_fitness() -> None:
    terms = np.array([[1.0, 1.0], [np.nan, 1.0], [1.0, 1.0], [1.0, np.inf]])
    failed = np.array([False, False, True, False])
    fitness = spec().combine(terms, failed, 9)
    assert fitness[0] == 2.5
    assert (fitness[1:] == WORST_FITNESS).all()


def test_spec_round_trips_and_checks_names() -> None:
    assert FitnessSpec.from_dict(spec().to_dict()) == spec()
    assert spec().names == ("goal", "style")
    with pytest.raises(FitnessError, match="needs a weight"):
        FitnessSpec(main="x", weights={"y": 1.0})
    with pytest.raises(FitnessError, match="finite"):
        FitnessSpec(main="x", weights={"x": float("nan")})
    with pytest.raises(FitnessError, match="malformed"):
        FitnessSpec.from_dict({"weights": {}})


def test_parse_weights() -> None:
    assert parse_weights("a=1, b=0.25,") == {"a": 1.0, "b": 0.25}
    with pytest.raises(FitnessError, match="name=number"):
        parse_weights("a=1,b")
    with pytest.raises(FitnessError, match="name=number"):
        parse_weights("a=x")
