"""A short stored GP run on the lamp: deterministic, replayable, rated by the phased-in weights."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest

from gp_helpers import stored

pytest.importorskip("mujoco")

from sinews.evolve import SerialEvaluator
from sinews.experiments.evolution import GenerationSummary
from sinews.experiments.gp.run import KIND as EXPERIMENT
from sinews.experiments.gp.settings import GPSettings
from sinews.experiments.gp.simulate import measure_programs
from sinews.experiments.run_config import EvolutionConfig
from sinews.store import RunStore

RUN = {"phase_in": {"start": 1, "full": 2},
       "strategy": {"name": "gp", "tournament_size": 2, "max_size": 40}}  # fmt: skip
OPTIONS = {"task": "hop", "target": "1.0", "population": 6, "generations": 3, "seconds": 1.0,
           "seed": 11}  # fmt: skip


def evolve(db: Path, on_generation: Callable[[GenerationSummary], None] | None = None) -> int:
    """A 6-program, 3-generation hop run in ``db``; its id."""
    with RunStore(db) as store:
        run = EXPERIMENT.create_run(store, subject="luxo", file_values=RUN, options=OPTIONS)
        EXPERIMENT.run(store, run, evaluator=SerialEvaluator(), on_generation=on_generation)
    return run


@pytest.fixture(scope="module")
def db(tmp_path_factory: pytest.TempPathFactory) -> Path:
    path = tmp_path_factory.mktemp("gp") / "runs.db"
    evolve(path)
    return path


def test_a_short_run_is_deterministic_and_reports_every_generation(
    db: Path, tmp_path: Path
) -> None:
    seen: list[GenerationSummary] = []
    evolve(tmp_path / "again.db", seen.append)
    assert [s.generation for s in seen] == [0, 1, 2]
    assert all(s.failed == 0 and s.best is not None and np.isfinite(s.best) for s in seen)
    status, individuals, checkpoints = stored(db)
    assert (status, len(individuals), len(checkpoints)) == ("finished", 18, 3)
    assert stored(tmp_path / "again.db") == (status, individuals, checkpoints)
    fitness = np.array([i.fitness for i in individuals]).reshape(3, 6)
    assert fitness.max(axis=1).tolist() == [s.best for s in seen]


def test_the_replayed_best_scores_as_it_did_in_its_generation(db: Path) -> None:
    with RunStore(db) as store:
        best = store.best(1)
        settings = GPSettings.from_values(store.run(1).config)
        (replay,) = EXPERIMENT.replay(store, [best], record_hz=20.0)
    alone = measure_programs(settings, settings.parse([best.genome]))
    assert dict(zip(settings.task.weights, alone.terms[0].tolist(), strict=True)) == best.terms
    qpos = replay.trajectory.qpos
    assert qpos is not None and replay.trajectory.fps == 20.0
    assert len(qpos) == 21  # 1 s at 20 frames/s, both ends
    assert best.terms is not None
    # the X is on the floor: x, and the base's height above rest (the slide z, 0 at rest)
    assert best.terms["distance"] == pytest.approx(-np.hypot(qpos[-1, 0] - 1.0, qpos[-1, 1]))


def test_generations_are_rated_by_the_phased_in_weights(db: Path) -> None:
    with RunStore(db) as store:
        spec = EvolutionConfig.from_dict(store.run(1).config).fitness
        table = store.scores(1)
    terms = np.array([[t[name] for name in spec.names] for t in table.terms])
    first, last = table.generation == 0, table.generation == 2
    np.testing.assert_array_equal(table.fitness[first], terms[first, 0])  # main goal only
    full = terms[last] @ np.array([spec.weights[name] for name in spec.names])
    np.testing.assert_allclose(table.fitness[last], full)
    assert (table.fitness[last] != terms[last, 0]).any()  # style counts in the end
    for generation in range(3):
        rows = table.generation == generation
        combined = spec.combine(terms[rows], table.failed[rows], generation)
        np.testing.assert_array_equal(table.fitness[rows], combined)


def test_programs_are_measured_by_the_tasks_terms() -> None:
    settings = GPSettings(task_name="luxo-hop", task_options={"target": 1.0}, seconds=1.0)
    still, crouch = settings.parse(["(list 0.0 0.0 0.0)", "(list 0.5 (* -1.0 time) gx)"])
    done = measure_programs(settings, [still, crouch])
    alone = measure_programs(settings, [crouch])
    np.testing.assert_array_equal(done.terms[1], alone.terms[0])  # the batch does not matter
    assert done.terms[0, 0] == pytest.approx(-1.0, abs=1e-3)  # standing still, 1 m from the X
    assert not done.failed.any() and (done.nonfinite == 0).all()
