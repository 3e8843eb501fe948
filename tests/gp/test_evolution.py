"""A short GP run on the lamp: deterministic, replayable, reporting each generation."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("mujoco")

from sinews.control.gp import parse_program
from sinews.evolve import PhaseIn
from sinews.evolve.gp import GPStrategy, GPVariation
from sinews.experiments.gp_figures import (
    GPGeneration,
    GPRun,
    GPSettings,
    Scored,
    evaluate_programs,
    primitive_set,
    run_gp,
)
from sinews.figures.tasks import luxo_hop

SETTINGS = GPSettings(
    population=6,
    generations=3,
    seconds=1.0,
    phase_in=PhaseIn(start=1, full=2),
    variation=GPVariation(tournament_size=2, max_size=40),
    record_hz=20.0,
)


def _run(seen: list[tuple[GPGeneration, bytes]] | None = None) -> GPRun:
    def keep(summary: GPGeneration, strategy: GPStrategy, scored: Scored) -> None:
        assert seen is not None
        assert len(strategy.population) == len(scored.fitness) == 6
        seen.append((summary, strategy.to_bytes()))

    return run_gp(
        luxo_hop(1.0), seed=11, settings=SETTINGS, on_generation=keep if seen is not None else None
    )


def test_a_short_run_is_deterministic_and_reports_every_generation() -> None:
    first: list[tuple[GPGeneration, bytes]] = []
    second: list[tuple[GPGeneration, bytes]] = []
    a, b = _run(first), _run(second)
    assert [g.generation for g, _ in first] == [0, 1, 2]
    for (summary_a, checkpoint_a), (summary_b, checkpoint_b) in zip(first, second, strict=True):
        assert checkpoint_a == checkpoint_b
        assert {**summary_a.__dict__, "seconds": 0} == {**summary_b.__dict__, "seconds": 0}
    assert a.best_text == b.best_text == first[-1][0].best_program
    assert a.best_terms == b.best_terms
    np.testing.assert_array_equal(a.trajectory.qpos, b.trajectory.qpos)
    assert a.trajectory.fps == 20.0 and a.trajectory.qpos is not None
    assert len(a.trajectory.qpos) == 21  # 1 s at 20 frames/s, both ends
    assert len(a.history) == 3 and np.isfinite(a.history[-1].best)


def test_the_replayed_best_scores_as_it_did_in_its_generation() -> None:
    seen: list[tuple[GPGeneration, bytes]] = []
    run = _run(seen)
    last = seen[-1][0]
    assert run.best_terms == last.best_terms  # alone or in a batch: the same motion
    assert run.best_terms["distance"] == pytest.approx(-abs(run.trajectory.qpos[-1, 0] - 1.0))


def test_evaluation_rates_by_the_phased_in_weights() -> None:
    task = luxo_hop(1.0)
    pset = primitive_set(task, SETTINGS)
    still = parse_program("(list 0.0 0.0 0.0)", pset)
    crouch = parse_program("(list 0.5 (* -1.0 time) gx)", pset)
    early = evaluate_programs(task, [still, crouch], 0, SETTINGS)
    late = evaluate_programs(task, [still, crouch], 2, SETTINGS)
    np.testing.assert_array_equal(early.terms, late.terms)
    np.testing.assert_array_equal(early.fitness, early.terms[:, 0])  # main goal only
    full = late.terms @ np.array(list(task.weights.values()))
    np.testing.assert_allclose(late.fitness, full)
    assert early.fitness[0] == pytest.approx(-1.0, abs=1e-3)
    assert not early.failed.any() and (early.nonfinite == 0).all()
