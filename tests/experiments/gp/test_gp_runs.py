"""GP runs in the store: one seed, one run on any executor; a run stopped by an error, cut
short or SIGKILLed resumes to the uninterrupted one bit for bit."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from gp_helpers import stored
from killed_runs import kill_when, stored_generations

pytest.importorskip("mujoco")

from sinews.cli import main
from sinews.evolve import SerialEvaluator
from sinews.experiments.evolution import GenerationSummary, _soft
from sinews.experiments.gp.run import KIND as EXPERIMENT
from sinews.experiments.gp.run import _summary
from sinews.experiments.run_config import EvolutionConfig
from sinews.figures.tasks import make_task
from sinews.store import RunStore

OPTIONS: dict[str, Any] = {"task": "hop", "target": "1.5", "population": 8, "generations": 8,
                           "seconds": 0.5, "seed": 3}  # fmt: skip


def arguments(**changes: Any) -> list[str]:
    """``evolve luxo --controller gp`` with `OPTIONS` (and ``changes``) as options."""
    options = {**OPTIONS, **changes}
    given = [part for key, value in options.items() for part in (f"--{key}", str(value))]
    return ["evolve", "luxo", "--controller", "gp", *given]


@pytest.fixture(scope="module")
def whole(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """An uninterrupted run of 8 generations."""
    db = tmp_path_factory.mktemp("whole") / "runs.db"
    assert main([*arguments(), "--db", str(db)]) == 0
    return db


def test_the_same_seed_gives_the_same_run_on_any_executor(whole: Path, tmp_path: Path) -> None:
    """Serial (one batch, every thread) and 2 processes (2 chunks, 1 thread each) agree."""
    again, pool, other = tmp_path / "again.db", tmp_path / "pool.db", tmp_path / "other.db"
    assert main([*arguments(), "--db", str(again)]) == 0
    assert main([*arguments(), "--executor", "processes", "--workers", "2", "--db", str(pool)]) == 0
    assert main([*arguments(seed=4, generations=1), "--db", str(other)]) == 0
    status, individuals, checkpoints = stored(whole)
    assert (status, len(individuals), len(checkpoints)) == ("finished", 64, 8)
    assert stored(again) == stored(pool) == (status, individuals, checkpoints)
    assert [i.genome for i in stored(other)[1]] != [i.genome for i in individuals[:8]]


class Stop(Exception):
    """Stands for a crash between two generations."""


def stop_after_generation_2(summary: GenerationSummary) -> None:
    if summary.generation == 2:
        raise Stop


@pytest.mark.parametrize("how", ["error", "fewer generations"])
def test_a_stopped_run_resumes_to_the_uninterrupted_one(
    how: str, whole: Path, tmp_path: Path
) -> None:
    cut = tmp_path / "cut.db"
    with RunStore(cut) as store:
        run = EXPERIMENT.create_run(store, subject="luxo", file_values={}, options=OPTIONS)
        if how == "error":
            with pytest.raises(Stop):
                EXPERIMENT.run(store, run, evaluator=SerialEvaluator(),
                               on_generation=stop_after_generation_2)  # fmt: skip
            assert store.run(run).status == "failed"
        else:
            EXPERIMENT.run(store, run, evaluator=SerialEvaluator(), generations=3)
            assert store.run(run).status == "finished"
        assert store.last_generation(run) == 2
    more = ["--generations", "8"] if how == "fewer generations" else []
    assert main(["runs", "resume", str(run), *more, "--db", str(cut)]) == 0
    assert stored(cut) == stored(whole)


def test_a_killed_run_resumes_to_the_uninterrupted_one(whole: Path, tmp_path: Path) -> None:
    cut = tmp_path / "cut.db"
    kill_when([*arguments(), "--db", str(cut)], cut, 3)
    assert 3 <= stored_generations(cut) < 8
    assert main(["runs", "resume", "1", "--db", str(cut)]) == 0
    assert stored(cut) == stored(whole)


def test_a_replay_says_how_far_from_the_goal_it_ends(whole: Path) -> None:
    """The main goal's own measure (the X, 1.5 m ahead), not how far the lamp travelled."""
    with RunStore(whole) as store:
        (info,) = store.runs()
        people = store.individuals(info.id, 7)[:2]
        for person, replay in zip(people, EXPERIMENT.replay(store, people), strict=True):
            distance = (person.terms or {})["distance"]
            assert distance is not None
            assert replay.summary == f"{-distance:.3f} m from the goal"


def test_a_held_goal_says_it_is_held() -> None:
    """A replay of a held goal reports its worst over the hold, in the goal's own unit."""
    point = make_task("humanoid3d-point", target=(2.0, -1.5, 2.2))
    nose = make_task("humanoid-reach", target="nose")
    hop = make_task("luxo-hop", target=1.0)
    assert _summary(point, np.array([-math.radians(2.5)])) == (
        "2.5° off the target at most over the last 0.5 s"
    )
    assert _summary(nose, np.array([-0.012])) == "0.012 m from the goal at most over the last 0.5 s"
    assert _summary(hop, np.array([-0.2])) == "0.200 m from the goal"


def test_a_run_stored_before_its_task_gained_a_term_goes_on_rated_by_its_own(
    tmp_path: Path,
) -> None:
    """luxo3d-hop gained ``spot``; a hop run stored without it resumes, rated as before."""
    options = {**OPTIONS, "target": "0.6,0.3", "population": 4, "generations": 2,
               "seconds": 0.2}  # fmt: skip
    with RunStore(tmp_path / "runs.db") as store:
        run = EXPERIMENT.create_run(store, subject="luxo3d", file_values={}, options=options)
        config = dict(store.run(run).config)
        fitness = dict(config["fitness"])
        assert fitness["weights"]["spot"] == 0.0
        fitness["weights"] = {k: v for k, v in fitness["weights"].items() if k != "spot"}
        store.update_config(run, {**config, "fitness": fitness})
        EXPERIMENT.run(store, run, evaluator=SerialEvaluator())
        table = store.scores(run)
        spec = EvolutionConfig.from_dict(store.run(run).config).fitness
    assert "spot" not in spec.names and "spot" in table.terms[0]
    terms = np.array([[t[name] for name in spec.names] for t in table.terms])
    for generation in range(2):
        rows = table.generation == generation
        combined = spec.combine(terms[rows], table.failed[rows], generation)
        np.testing.assert_array_equal(table.fitness[rows], combined)


@pytest.mark.parametrize("selection", ["soft_share = 0.5", 'selection = "pareto"'])
def test_soft_breeding_is_told_the_weighted_sums_and_resumes_bit_for_bit(
    whole: Path, tmp_path: Path, selection: str
) -> None:
    """Stochastic ranking (``soft_share``) or Pareto tournaments with the constraints from
    generation 0: the strategy hears each generation's sums without the ranking; a cut run
    resumes."""
    config = tmp_path / "soft.toml"
    config.write_text('constraints = ["head", "fallen"]\nphase_in = { start = 0, full = 7 }\n'
                      f'[strategy]\nname = "gp"\n{selection}\n')  # fmt: skip
    soft, cut = tmp_path / "soft.db", tmp_path / "cut.db"
    assert main([*arguments(), "--config", str(config), "--db", str(soft)]) == 0
    assert main([*arguments(generations=3), "--config", str(config), "--db", str(cut)]) == 0
    assert main(["runs", "resume", "1", "--generations", "8", "--db", str(cut)]) == 0
    assert stored(cut) == stored(soft) != stored(whole)
    with RunStore(soft) as store:
        spec = EvolutionConfig.from_dict(store.run(1).config).fitness
        table = store.scores(1)
        told = [_soft(store, 1, g, spec, g) for g in range(8)]
    ranked = [g for g, sums in enumerate(told) if sums is not None]
    assert ranked == list(range(8))
    faulty_all = np.array([(t["head"] or 0) < 0 or (t["fallen"] or 0) < 0 for t in table.terms])
    reordered = 0
    for g, sums in enumerate(told):
        assert sums is not None
        fitness, faulty = table.fitness[table.generation == g], faulty_all[table.generation == g]
        np.testing.assert_array_equal(sums[~faulty], fitness[~faulty])  # the clean: the same
        assert fitness[faulty].max(initial=-np.inf) < fitness[~faulty].min(initial=np.inf)
        reordered += sums[faulty].max(initial=-np.inf) > sums[~faulty].min(initial=np.inf)
    assert reordered  # the sums put a faulty program above a clean one
