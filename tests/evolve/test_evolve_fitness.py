"""Fitness specs: weights, the phase-in schedule, constraints, failures, parsing."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from sinews.evolve import WORST_FITNESS, FitnessError, FitnessSpec, PhaseIn, parse_weights
from sinews.experiments.evolution import full_weight_fitness, retune_fitness
from sinews.store import RunStore


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


def constrained(start: int = 1) -> FitnessSpec:
    return FitnessSpec(
        main="goal",
        weights={"goal": 1.0, "head": 1.0, "fallen": 2.0},
        phase_in=PhaseIn(start=start, full=start + 1),
        constraints=("head", "fallen"),
    )


def test_constraints_rank_every_clean_individual_first() -> None:
    terms = np.array(
        [
            [-0.50, 0.0, 0.0],  # clean, far: -0.5
            [-0.01, -0.02, 0.0],  # near, touches: loses 0.02
            [-1.00, 0.0, 0.0],  # clean, farther: the floor, -1.0
            [-0.02, -0.002, -0.001],  # near, loses 0.003
            [np.nan, 0.0, 0.0],  # failed
        ]
    )
    failed = np.zeros(5, dtype=bool)
    before = constrained(start=3).combine(terms, failed, 2)
    np.testing.assert_allclose(before[:4], terms[:4, 0])  # before the start: the goal only
    after = constrained().combine(terms, failed, 5)
    np.testing.assert_allclose(after, [-0.5, -1.02, -1.0, -1.003, WORST_FITNESS])
    assert list(np.argsort(-after)) == [0, 2, 3, 1, 4]


def test_without_a_clean_individual_the_least_loss_wins() -> None:
    terms = np.array([[0.0, -0.5, 0.0], [-3.0, 0.0, -0.1], [-1.0, -0.2, -0.2]])
    fitness = constrained().combine(terms, np.array([False, False, True]), 4)
    np.testing.assert_allclose(fitness, [-0.5, -0.1, WORST_FITNESS])


def test_constraints_round_trip_and_must_be_style_terms() -> None:
    assert FitnessSpec.from_dict(constrained().to_dict()) == constrained()
    assert "constraints" not in spec().to_dict()  # an old run's config is unchanged
    assert FitnessSpec.from_dict(spec().to_dict()).constraints == ()
    for bad in (("goal",), ("toes",), ("head", "head")):
        with pytest.raises(FitnessError, match="constraint"):
            FitnessSpec(main="goal", weights={"goal": 1.0, "head": 1.0}, constraints=bad)
    with pytest.raises(FitnessError, match="malformed"):
        FitnessSpec.from_dict({**constrained().to_dict(), "constraints": "head"})


def test_constraints_from_breeds_by_the_weights_first_and_the_best_is_always_clean() -> None:
    later = dataclasses.replace(constrained(), constraints_from=50)  # past a 50-generation run
    assert later.constraints_start == 50 and later.final == 50
    assert constrained().constraints_start == 1 and constrained().final == 2
    terms = np.array([[-0.03, -0.01, 0.0], [-0.04, 0.0, 0.0]])  # near and touching; clean
    failed = np.zeros(2, dtype=bool)
    breeding = later.combine(terms, failed, 49)  # full style weight, no ranking yet
    np.testing.assert_allclose(breeding, [-0.04, -0.04])
    best = later.combine(terms, failed, later.final)  # how the run's best is chosen
    assert best[1] > best[0]
    stored = [
        {"goal": -0.03, "head": -0.01, "fallen": 0.0},
        {"goal": -0.04, "head": 0.0, "fallen": 0.0},
    ]
    assert np.argmax(full_weight_fitness(stored, [False, False], later)) == 1
    assert FitnessSpec.from_dict(later.to_dict()) == later
    assert "constraints_from" not in constrained().to_dict()


@pytest.mark.parametrize("value", [-1, True, 2.5, "5", 10**9])
def test_constraints_from_must_be_a_generation(value: object) -> None:
    with pytest.raises(FitnessError, match="constraints_from must be a generation"):
        FitnessSpec(main="goal", weights={"goal": 1.0, "head": 1.0}, constraints=("head",),
                    constraints_from=value)  # type: ignore[arg-type]  # fmt: skip
    with pytest.raises(FitnessError, match="needs constraints"):
        FitnessSpec(main="goal", weights={"goal": 1.0}, constraints_from=3)


def test_retuning_a_run_keeps_its_constraints(tmp_path: Path) -> None:
    with RunStore(tmp_path / "r.db") as store:
        config = {"fitness": constrained().to_dict()}
        run_id = store.create_run("gp-luxo", config=config, seed=0, genome_codec="json")
        new = retune_fitness(store, run_id, {"fallen": 4.0}, PhaseIn(0, 3))
        assert new.constraints == ("head", "fallen") and new.weights["fallen"] == 4.0
        assert FitnessSpec.from_dict(store.run(run_id).config["fitness"]) == new
