"""The motion a studio pick simulated while scoring replays exactly as a fresh simulation."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("mujoco")

from sinews.cli import main
from sinews.evolve import SerialEvaluator
from sinews.experiments.kinds import RunKind, kind_of
from sinews.experiments.motion_log import MotionLog
from sinews.store import Individual, RunStore

RUNS = {
    "springnet": ["luxo", "--population", "10", "--generations", "1", "--seconds", "1"],
    "gp": ["luxo", "--controller", "gp", "--task", "hop", "--population", "6", "--generations",
           "1", "--seconds", "1"],
    "gp3d": ["luxo3d", "--controller", "gp", "--task", "hop", "--population", "6",
             "--generations", "1", "--seconds", "0.5"],
}  # fmt: skip


def key(individual: Individual) -> object:
    """What the kind's scorer names a genome by: a program's text, a net's gene bytes."""
    genome = individual.genome
    return genome if isinstance(genome, str) else np.asarray(genome, np.float64).tobytes()


@pytest.mark.parametrize(
    ("controller", "how"),
    [(c, "pick") for c in sorted(RUNS)] + [("gp", "run"), ("springnet", "run")],
)
def test_scoring_logs_the_motion_that_replays_exactly(
    controller: str, how: str, tmp_path: Path
) -> None:
    """A studio pick, or a background job extending a run by a generation, keeps the motion
    it simulated while scoring, and a replay from the log equals a fresh simulation."""
    db = tmp_path / "runs.db"
    assert main(["evolve", *RUNS[controller], "--seed", "5", "--db", str(db)]) == 0
    log = MotionLog(50.0)
    with RunStore(db) as store:
        (info,) = store.runs()
        kind = kind_of(info)
        if how == "pick":
            kind.pick(store, info.id, 0, [0, 1], log=log)
        else:
            kind.run(store, info.id, evaluator=SerialEvaluator(), generations=2, log=log)
        assert_replays_from_the_log(kind, store, store.individuals(info.id, 1), log, controller)


def assert_replays_from_the_log(
    kind: RunKind, store: RunStore, people: list[Individual], log: MotionLog, controller: str
) -> None:
    """Every individual's motion is in ``log`` and replays exactly as a fresh simulation."""
    assert all(log.get(key(p)) is not None for p in people)  # every one was recorded
    logged = kind.replay(store, people, record_hz=50.0, log=log)
    fresh = kind.replay(store, people, record_hz=50.0)
    assert kind.replay(store, people, record_hz=30.0, log=log)[0].trajectory.fps == 30.0
    for a, b in zip(logged, fresh, strict=True):
        assert (a.summary, a.distance, a.title) == (b.summary, b.distance, b.title)
        for name in ("positions", "qpos", "body_pos"):
            np.testing.assert_array_equal(getattr(a.trajectory, name), getattr(b.trajectory, name))
        assert a.trajectory.fps == b.trajectory.fps == 50.0
        if controller == "springnet":
            np.testing.assert_array_equal(a.panel.positions, b.panel.positions)


def test_the_log_keeps_the_newest_genomes() -> None:
    log = MotionLog(50.0, capacity=2)
    for name in ("a", "b", "a", "c"):
        log.put(name, name.upper())
    assert [log.get(name) for name in ("a", "b", "c")] == ["A", None, "C"]
