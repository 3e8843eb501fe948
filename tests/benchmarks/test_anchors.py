"""The benchmarks' anchors compute what we compute: DEAP's lambdas and Taichi's frame loop."""

from __future__ import annotations

import numpy as np
import pytest

from sinews.control.gp import FUNCTIONS, PackedPopulation, PrimitiveSet, ramped_half_and_half

pytest.importorskip("deap")


def test_deap_lambdas_answer_what_our_interpreter_answers() -> None:
    from sinews.benchmarks._deap import DeapPopulation

    pset = PrimitiveSet(terminals=("a", "b", "c", "d"), functions=tuple(FUNCTIONS))
    programs = ramped_half_and_half(pset, np.random.default_rng(3), n_programs=40, n_trees=3)
    inputs = np.random.default_rng(4).normal(size=(40, 4)) * 10.0
    inputs[::7, 1] = 0.0  # protected division
    inputs[3, :] = [np.inf, -np.inf, np.nan, 1e308]  # overflow, NaN conditions, cos(inf)
    ours = PackedPopulation.pack(programs).evaluate(inputs)
    lambdas = DeapPopulation(programs, pset)
    lambdas.compile()
    theirs = lambdas.evaluate(inputs, np.empty_like(ours))
    np.testing.assert_array_equal(theirs, ours)


def test_deap_breeding_gives_a_whole_next_generation() -> None:
    from sinews.benchmarks._deap import DeapPopulation

    pset = PrimitiveSet(terminals=("a", "b"))
    programs = ramped_half_and_half(pset, np.random.default_rng(0), n_programs=10, n_trees=3)
    lambdas = DeapPopulation(programs, pset)
    fitness = np.arange(10.0)
    first, again = lambdas.breed(fitness, seed=1), lambdas.breed(fitness, seed=1)
    assert [len(trees) for trees in first] == [3] * 10
    assert [[str(t) for t in trees] for trees in first] == [
        [str(t) for t in trees] for trees in again
    ]


def test_deaps_way_rates_each_program_as_our_generation_does() -> None:
    pytest.importorskip("mujoco")
    from sinews.benchmarks.gp import _rate_alone
    from sinews.experiments.gp.settings import GPSettings
    from sinews.experiments.gp.simulate import measure_programs

    settings = GPSettings(task_name="luxo-hop", task_options={"target": 1.0}, seconds=0.3)
    programs = ramped_half_and_half(settings.pset, np.random.default_rng(2), n_programs=3,
                                    n_trees=3)  # fmt: skip
    ours = measure_programs(settings, programs)
    alone = np.stack([_rate_alone(settings, program) for program in programs])
    assert not ours.failed.any()
    np.testing.assert_array_equal(alone, ours.terms)


def test_taichi_frame_loop_ends_where_ours_does() -> None:
    pytest.importorskip("taichi")
    from sinews.benchmarks import _taichi
    from sinews.benchmarks.springmass import _crowd
    from sinews.dancers import DANCER_ENGINE
    from sinews.springmass import simulate

    _taichi.start(threads=1)
    batch = _crowd(3)
    state = batch.initial_state()
    ours, _ = simulate(batch, state, 50, DANCER_ENGINE, record=False)
    crowd = _taichi.TaichiCrowd(batch, DANCER_ENGINE, state.positions)
    crowd.run(50)
    np.testing.assert_allclose(crowd.positions(), ours.positions, rtol=0, atol=1e-9)
    assert np.abs(ours.positions - state.positions).max() > 1e-3  # they moved
