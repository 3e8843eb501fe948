"""Run settings (TOML + options), the interactive picks hook, extending and replaying runs."""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from sinews.errors import SinewsError
from sinews.evolve import SerialEvaluator
from sinews.experiments.dancers import score as dancer_fitness
from sinews.experiments.dancers.run import GENOMES, KIND, run_music
from sinews.experiments.dancers.score import beat_align
from sinews.experiments.dancers.settings import dancer_config, song_path
from sinews.experiments.evolution import Strategies, record_picks
from sinews.experiments.run_config import EvolutionConfig, load_toml
from sinews.store import RunStore, generation_stats
from sinews.trajectory import Trajectory

SONG = str(Path(__file__).resolve().parents[2] / "data" / "loop_mika.flac")


@pytest.fixture(autouse=True)
def _private_dirs(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("XDG_DATA_HOME", str(tmp_path / "data"))
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))


def write_toml(tmp_path: Path, text: str) -> dict[str, object]:
    path = tmp_path / "run.toml"
    path.write_text(text)
    return load_toml(path)


def test_options_override_the_run_file_which_overrides_defaults(tmp_path: Path) -> None:
    file_values = write_toml(
        tmp_path,
        'song = "demo:sway"\npopulation = 12\nseed = 3\nfitness = ["beat-align", "variety"]\n'
        "weights = { variety = 0.7 }\nphase_in = { start = 2, full = 4 }\n"
        '[strategy]\nname = "hybrid"\nelites = 2\npick_mode = "override"\n',
    )
    config, song, seconds = dancer_config(
        file_values=file_values, options={"population": 8, "seconds": 5.0, "seed": None}
    )
    assert (config.population, config.seed, config.generations) == (8, 3, 20)
    assert (song, seconds) == ("demo:sway", 5.0)
    assert config.fitness.names == ("beat-align", "variety")
    assert config.fitness.weights == {"beat-align": 1.0, "variety": 0.7}
    assert (config.fitness.phase_in.start, config.fitness.phase_in.full) == (2, 4)
    assert config.strategy == "hybrid"
    assert config.strategy_options == {"elites": 2, "pick_mode": "override"}
    assert EvolutionConfig.from_dict(config.to_dict()) == config


@pytest.mark.parametrize(
    ("options", "message"),
    [
        ({}, "give a song"),
        ({"fitness": "beat-align,grace"}, "no fitness term called 'grace'"),
        ({"fitness": "beat-align", "weights": "variety=1"}, "not one of the --fitness terms"),
        ({"fitness": "beat-align,beat-align"}, "twice"),
        ({"phase_in": "soon"}, "START:FULL"),
        ({"phase_in": "9:3"}, "start <= full"),
        ({"population": 1}, "population must be a whole number from 2 to"),
        ({"seconds": -1.0}, "seconds must be a positive number"),
        ({"seconds": "long"}, "seconds must be a positive number"),
    ],
)
def test_bad_settings_are_one_line_errors(options: dict[str, object], message: str) -> None:
    with pytest.raises(SinewsError, match=message):
        dancer_config(file_values={}, options={"song": SONG, **options} if options else {})


def test_bad_run_files_are_refused(tmp_path: Path) -> None:
    with pytest.raises(SinewsError, match="unknown setting 'colour'"):
        dancer_config(file_values=write_toml(tmp_path, 'colour = "red"\n'), options={})
    (tmp_path / "broken.toml").write_text("population = \n")
    with pytest.raises(SinewsError, match="not valid TOML"):
        load_toml(tmp_path / "broken.toml")
    with pytest.raises(SinewsError, match="cannot read"):
        load_toml(tmp_path / "missing.toml")


def test_demo_songs_are_written_once_to_the_data_dir(tmp_path: Path) -> None:
    path = song_path("demo:groove")
    assert path == tmp_path / "data" / "sinews" / "songs" / "groove.wav"
    stamp = path.stat().st_mtime_ns
    assert song_path("demo:groove").stat().st_mtime_ns == stamp
    with pytest.raises(SinewsError, match="no demo song 'polka'"):
        song_path("demo:polka")


def start(store: RunStore, **options: object) -> int:
    return KIND.create_run(store, subject="dancers", file_values={}, options={
        "song": SONG, "population": 6, "generations": 2, "seconds": 2.0, **options,
    })  # fmt: skip


def test_interactive_run_advances_by_picks_in_one_transaction(tmp_path: Path) -> None:
    with RunStore(tmp_path / "runs.db") as store:
        run = start(store, strategy="interactive")
        KIND.run(store, run, evaluator=SerialEvaluator())
        assert store.last_generation(run) == 0 and store.run(run).status == "running"
        summary = KIND.pick(store, run, 0, [1, 4])
        assert summary.generation == 1 and summary.best is None  # by hand: not scored
        before, after = store.individuals(run, 0), store.individuals(run, 1)
        assert [i.picked for i in before] == [False, True, False, False, True, False]
        np.testing.assert_array_equal(after[0].genome, before[1].genome)
        picked_ids = {before[1].id, before[4].id}
        assert all(set(i.parents) <= picked_ids and i.parents for i in after)
        with pytest.raises(SinewsError, match="picks are for generation 1, not 0"):
            KIND.pick(store, run, 0, [2])
        record_picks(store, run, 1, [], strategies=Strategies(GENOMES))
        fresh = store.individuals(run, 2)
        assert fresh[0].fitness is None and all(not i.parents for i in fresh)


def test_a_ga_run_refuses_picks_and_can_be_extended(tmp_path: Path) -> None:
    with RunStore(tmp_path / "runs.db") as store:
        run = start(store)
        KIND.run(store, run, evaluator=SerialEvaluator())
        assert store.run(run).status == "finished"
        with pytest.raises(SinewsError, match="does not take picks"):
            record_picks(store, run, 1, [0], strategies=Strategies(GENOMES))
        KIND.run(store, run, evaluator=SerialEvaluator(), generations=3)
        info = store.run(run)
        assert (info.generations, info.status, info.config["generations"]) == (3, "finished", 3)
        for individual in store.individuals(run, 2):
            ancestry = store.lineage(individual.id)
            assert ancestry[-1].generation == 0
            assert all(a.parents for a in ancestry if a.generation > 0)
        with pytest.raises(SinewsError, match="already has 3 generations"):
            KIND.run(store, run, evaluator=SerialEvaluator(), generations=2)


def test_replaying_an_individual_reproduces_its_fitness(tmp_path: Path) -> None:
    with RunStore(tmp_path / "runs.db") as store:
        run = start(store, fitness="beat-align")
        KIND.run(store, run, evaluator=SerialEvaluator())
        best = store.best(run)
        (replay,) = KIND.replay(store, [best])
        traj, path = replay.trajectory, replay.audio
        assert path == Path(SONG)
        assert traj.duration == pytest.approx(2.0, abs=0.05)
        assert beat_align(traj) == best.fitness


def test_a_changed_song_is_detected(tmp_path: Path) -> None:
    song = tmp_path / "song.flac"
    song.write_bytes(Path(SONG).read_bytes())
    with RunStore(tmp_path / "runs.db") as store:
        run = KIND.create_run(store, subject="dancers", file_values={},
                              options={"song": str(song), "seconds": 1.0})  # fmt: skip
        song.write_bytes((Path(SONG).parent / "loop_compus.flac").read_bytes())
        with pytest.raises(SinewsError, match="the song has changed since run 1 started"):
            run_music(store.run(run))


def test_blown_up_dancers_get_the_worst_fitness_and_the_run_goes_on(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    real_dance = dancer_fitness.dance

    def first_blows_up(*args: Any, **kwargs: Any) -> list[Trajectory]:
        trajs = real_dance(*args, **kwargs)
        return [dataclasses.replace(trajs[0], failed=True), *trajs[1:]]

    monkeypatch.setattr(dancer_fitness, "dance", first_blows_up)
    with RunStore(tmp_path / "runs.db") as store:
        run = start(store, generations=3)
        KIND.run(store, run, evaluator=SerialEvaluator())
        assert store.run(run).status == "finished"
        for generation in range(3):
            first, *others = store.individuals(run, generation)
            assert first.failed and first.fitness == -math.inf
            assert first.terms == dict.fromkeys(first.terms or {}) and first.terms
            assert all(not i.failed and math.isfinite(i.fitness or math.nan) for i in others)
        elite = store.individuals(run, 1)[0]
        assert store.individual(elite.parents[0]).index != 0
        stats = generation_stats(store.scores(run))
        assert stats.failed.tolist() == [1, 1, 1] and np.isfinite(stats.mean).all()
