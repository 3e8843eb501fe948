"""Spring-net figure runs: determinism, executors, hand picks, lineage, replay, resume."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pytest

from killed_runs import kill_when, stored_generations

pytest.importorskip("mujoco")

from sinews.cli import main
from sinews.errors import SinewsError
from sinews.evolve import ProcessEvaluator, SerialEvaluator
from sinews.experiments.figures import parse_keep
from sinews.experiments.kinds import kind_of, run_kind
from sinews.experiments.springnet.run import KIND as EXPERIMENT
from sinews.experiments.springnet.settings import SpringNetSettings
from sinews.store import RunStore

TINY = {"population": 10, "generations": 3, "seconds": 0.5, "seed": 3}


def contents(db: Path) -> list[Any]:
    """Everything a run stored that must not depend on how it was run."""
    with RunStore(db) as store:
        (info,) = store.runs()
        rows: list[Any] = [(info.kind, info.status, info.generations)]
        rows += [(i.generation, i.index, i.genome.tobytes(), i.fitness, i.terms, i.failed,
                  len(i.parents), i.picked) for i in store.individuals(info.id)]  # fmt: skip
        rows += [store.checkpoint(info.id, g) for g in range(info.generations)]
    return rows


def evolve(db: Path, evaluator: Any = None, **options: Any) -> int:
    with RunStore(db) as store:
        run = EXPERIMENT.create_run(store, subject="snake", file_values={},
                                    options={**TINY, **options})  # fmt: skip
        EXPERIMENT.run(store, run, evaluator=evaluator or SerialEvaluator())
    return run


def test_same_seed_same_run_whatever_the_executor(tmp_path: Path) -> None:
    """Serial (one batch, every thread) and 2 processes (2 chunks, 1 thread each) agree."""
    evolve(tmp_path / "a.db")
    evolve(tmp_path / "b.db")
    with ProcessEvaluator(workers=2) as pool:
        evolve(tmp_path / "c.db", pool)
    assert contents(tmp_path / "a.db") == contents(tmp_path / "b.db")
    assert contents(tmp_path / "a.db") == contents(tmp_path / "c.db")
    evolve(tmp_path / "d.db", seed=4)
    assert contents(tmp_path / "a.db")[1:] != contents(tmp_path / "d.db")[1:]


def test_a_run_stores_the_papers_generations(tmp_path: Path) -> None:
    run = evolve(tmp_path / "r.db", generations=2, keep={0: [0]})
    with RunStore(tmp_path / "r.db") as store:
        info = store.run(run)
        assert info.kind == "springnet-snake" and kind_of(info) is EXPERIMENT
        assert info.config["strategy"]["name"] == "alton" and info.config["masses"] == 4
        assert info.config["physics_hz"] == 500 and info.config["keep"] == {"0": [0]}
        first, second = store.individuals(run, 0), store.individuals(run, 1)
        fitness = np.array([i.fitness for i in first])
        assert first[0].picked and sum(i.picked for i in first) == 1
        survivors = [0, *[k for k in np.argsort(-fitness, kind="stable") if k != 0][:1]]
        assert [p.parents for p in second[:2]] == [(first[k].id,) for k in survivors]
        np.testing.assert_array_equal(second[0].genome, first[0].genome)  # kept by hand
        assert [len(i.parents) for i in second] == [1] * 8 + [0] * 2  # newcomers: none
        assert all(i.terms is not None and i.fitness == i.terms["distance"] for i in second)
        assert (np.array([i.fitness for i in second]) >= 0).all()  # |x_end - x_start|
        best = store.best(run)
        (replay,) = EXPERIMENT.replay(store, [best])
        assert abs(replay.distance) == best.fitness  # replayed exactly as scored
        assert replay.panel is not None and replay.trajectory.qpos is not None
        assert replay.panel.positions.shape == (replay.trajectory.n_frames, 4)
        document = EXPERIMENT.genome_document(store, best)
        assert document["kind"] == "springnet" and len(document["springs"]) == 4


def test_a_killed_run_resumes_to_the_uninterrupted_one(tmp_path: Path) -> None:
    """SIGKILL mid-run, then resume: the same genomes, fitness, lineage and checkpoints.

    The resumed scorer starts without its memory of the last generation and
    simulates the survivors again: the numbers must not change.
    """
    settings = ["--population", "12", "--generations", "14", "--seconds", "1", "--seed", "8",
                "--executor", "serial"]  # fmt: skip
    whole, cut = tmp_path / "whole.db", tmp_path / "cut.db"
    assert main(["evolve", "snake", *settings, "--db", str(whole)]) == 0
    kill_when(["evolve", "snake", *settings, "--db", str(cut)], cut, 3)
    assert 3 <= stored_generations(cut) < 14
    assert main(["runs", "resume", "1", "--db", str(cut)]) == 0
    assert contents(cut) == contents(whole)


def test_the_studio_hook_keeps_picks_and_breeds_the_next(tmp_path: Path) -> None:
    run = evolve(tmp_path / "p.db", generations=1)
    with RunStore(tmp_path / "p.db") as store:
        summary = run_kind("springnet").pick(store, run, 0, [7])
        assert summary.generation == 1
        assert store.individuals(run, 0)[7].picked
        assert store.individuals(run, 1)[0].parents == (store.individuals(run, 0)[7].id,)
        with pytest.raises(SinewsError, match="picks are for generation 1"):
            EXPERIMENT.pick(store, run, 0, [1])


@pytest.mark.parametrize(
    ("values", "message"),
    [({"figure": "dog"}, "no figure called 'dog'"), ({"seconds": -1}, "seconds must be"),
     ({"masses": 1}, "masses must be"), ({"physics_hz": 333}, "control_hz must divide")],
)  # fmt: skip
def test_bad_settings_name_the_setting(values: dict[str, Any], message: str) -> None:
    with pytest.raises(SinewsError, match=message):
        SpringNetSettings.from_values({"figure": "luxo", "seconds": 1.0, "control_hz": 100,
                                       **values})  # fmt: skip


def test_keep_files_are_parsed_and_checked() -> None:
    assert parse_keep("# picks\n0: 3 4\n\n2: 7, 1  # note\n5:\n") == {0: [3, 4], 2: [7, 1], 5: []}
    for text, message in [("0 3 4", "line 1"), ("0: 1\n0: 2", "given twice"),
                          ("1: 2 2", "repeated"), ("x: 1", "line 1")]:  # fmt: skip
        with pytest.raises(SinewsError, match=message):
            parse_keep(text)
