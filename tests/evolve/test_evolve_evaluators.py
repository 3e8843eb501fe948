"""Evaluators: chunking, and identical runs on serial, processes and Dask."""

from __future__ import annotations

import importlib.util
import operator
from pathlib import Path

import numpy as np
import pytest

from sinews.dancers import DancerGenome
from sinews.errors import SinewsError
from sinews.evolve import chunk_slices, make_evaluator
from sinews.experiments.dancers.run import KIND
from sinews.store import RunStore

SONG = str(Path(__file__).resolve().parents[1] / "data" / "loop_mika.flac")
HAS_DASK = importlib.util.find_spec("distributed") is not None


def private_dirs(monkeypatch: pytest.MonkeyPatch, home: Path) -> None:
    """Keep demo songs and song analyses out of the user's own directories."""
    monkeypatch.setenv("XDG_DATA_HOME", str(home / "data"))
    monkeypatch.setenv("XDG_CACHE_HOME", str(home / "cache"))


@pytest.fixture(autouse=True)
def _private_dirs(
    tmp_path_factory: pytest.TempPathFactory, monkeypatch: pytest.MonkeyPatch
) -> None:
    private_dirs(monkeypatch, tmp_path_factory.getbasetemp() / "xdg")


def test_chunk_slices_cover_the_population_in_order() -> None:
    slices = chunk_slices(10, 3)
    assert [(s.start, s.stop) for s in slices] == [(0, 4), (4, 8), (8, 10)]
    assert chunk_slices(2, 8) == [slice(0, 1), slice(1, 2)]
    assert chunk_slices(5, 1) == [slice(0, 5)]


def test_unknown_executor_and_stray_scheduler_are_refused() -> None:
    with pytest.raises(SinewsError, match="no executor called 'gpu'"):
        make_evaluator("gpu")
    with pytest.raises(SinewsError, match="--scheduler needs --executor dask"):
        make_evaluator("serial", scheduler="tcp://127.0.0.1:8786")


def evolve(tmp_path: Path, executor: str) -> tuple[np.ndarray, np.ndarray, str]:
    options = {"song": SONG, "population": 5, "generations": 3, "seed": 4, "seconds": 2.0,
               "phase_in": "0:1"}  # fmt: skip
    with RunStore(tmp_path / f"{executor}.db") as store:
        run_id = KIND.create_run(store, subject="dancers", file_values={}, options=options)
        with make_evaluator(executor, workers=2) as evaluator:
            assert evaluator.n_workers == (1 if executor == "serial" else 2)
            KIND.run(store, run_id, evaluator=evaluator)
        individuals = store.individuals(run_id)
        status = store.run(run_id).status
    genomes = np.array([ind.genome for ind in individuals])
    fitness = np.array([ind.fitness for ind in individuals])
    return genomes, fitness, status


EXECUTORS = [
    "processes",
    pytest.param(
        "dask", marks=pytest.mark.skipif(not HAS_DASK, reason="dask[distributed] not installed")
    ),
]


@pytest.fixture(scope="module")
def serial_run(tmp_path_factory: pytest.TempPathFactory) -> tuple[np.ndarray, np.ndarray, str]:
    with pytest.MonkeyPatch.context() as monkeypatch:
        private_dirs(monkeypatch, tmp_path_factory.getbasetemp() / "xdg")
        return evolve(tmp_path_factory.mktemp("serial"), "serial")


@pytest.mark.slow
@pytest.mark.parametrize("executor", EXECUTORS)
def test_runs_are_identical_on_every_executor(
    tmp_path: Path, executor: str, serial_run: tuple[np.ndarray, np.ndarray, str]
) -> None:
    genomes, fitness, status = serial_run
    assert status == "finished" and genomes.shape == (15, DancerGenome.SIZE)
    assert np.isfinite(fitness).all()
    other_genomes, other_fitness, _ = evolve(tmp_path, executor)
    np.testing.assert_array_equal(other_genomes, genomes)
    np.testing.assert_array_equal(other_fitness, fitness)


@pytest.mark.slow
@pytest.mark.skipif(not HAS_DASK, reason="dask[distributed] not installed")
def test_dask_connects_to_a_scheduler_address() -> None:
    from sinews.evolve import DaskEvaluator

    with (
        DaskEvaluator(workers=1) as local,
        make_evaluator("dask", scheduler=local.address) as remote,
    ):
        assert remote.n_workers == 1
        assert remote.map(operator.mul, 3, [1, 2, 3]) == [3, 6, 9]
