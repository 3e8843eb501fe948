"""Studio runs, motion packs and the live dancer, without a server."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest

from sinews.music import DEFAULT_DEMO
from sinews.store import RunStore
from sinews.studio.live import Grab, LiveDancer
from sinews.studio.motion import Motion
from sinews.studio.pack import encode_pack, millimetres
from sinews.studio.runs import MAX_SECONDS, StudioError, StudioRuns
from sinews.studio.songs import SongError, SongLibrary
from studio_helpers import decode_pack


@pytest.fixture
def runs(tmp_path: Path, studio_home: None) -> Iterator[StudioRuns]:
    with RunStore(tmp_path / "studio.db") as store:
        yield StudioRuns(store, SongLibrary(tmp_path / "songs"))


def test_a_pack_carries_its_header_and_aligned_arrays() -> None:
    arrays: dict[str, np.ndarray] = {
        "a": np.arange(5, dtype=np.int16),
        "b": np.ones((2, 3), np.float32),
        "c": np.array([True, False]),
    }
    header, decoded = decode_pack(encode_pack({"run": 3}, arrays))
    assert header["run"] == 3
    assert decoded["a"].tolist() == list(range(5))
    assert decoded["b"].shape == (2, 3) and decoded["b"].dtype == np.float32
    assert decoded["c"].tolist() == [1, 0]
    with pytest.raises(ValueError, match="reserved"):
        encode_pack({"arrays": 1}, {})
    with pytest.raises(ValueError, match="cannot be packed"):
        encode_pack({}, {"d": np.zeros(2, np.float64)})


def test_millimetres_round_clip_and_zero_nan() -> None:
    metres = np.array([0.0014, -0.0016, np.nan, 40.0, -1e9, 1.0])
    assert millimetres(metres).tolist() == [1, -2, 0, 32767, -32767, 1000]


def test_a_new_run_is_an_unscored_interactive_generation(runs: StudioRuns) -> None:
    run = runs.get(runs.create(runs.songs.demo(), seed=4))
    assert run.last == 0 and run.population == 16 and run.bpm is None
    assert run.song.id == f"demo-{DEFAULT_DEMO}"
    assert run.seconds == min(MAX_SECONDS, runs.music(run.id)[0].duration)
    people = runs.store.individuals(run.id, 0)
    assert len(people) == 16 and all(p.fitness is None and not p.parents for p in people)
    assert runs.store.run(run.id).config["strategy"]["name"] == "interactive"


def test_one_pick_is_mutated_with_the_chosen_strength(runs: StudioRuns) -> None:
    run_id = runs.create(runs.songs.demo(), seed=4)
    pick = runs.store.individuals(run_id, 0)[3]
    runs.breed(run_id, 0, [3], mutation=0.0)
    copies = runs.store.individuals(run_id, 1)
    assert all(p.parents == (pick.id,) for p in copies)
    assert all(np.array_equal(p.genome, pick.genome) for p in copies)
    assert runs.store.individual(pick.id).picked
    runs.breed(run_id, 1, [0], mutation=0.3)
    mutants = runs.store.individuals(run_id, 2)
    assert sum(not np.array_equal(p.genome, pick.genome) for p in mutants) >= 14


def test_bad_picks_change_nothing(runs: StudioRuns) -> None:
    run_id = runs.create(runs.songs.demo(), seed=4)
    runs.breed(run_id, 0, [1], mutation=0.1)
    before = len(runs.store.runs())
    for picks, mutation in (([1, 1], 0.1), ([16], 0.1), ([-1], 0.1), ([2], 0.9)):
        with pytest.raises(StudioError):
            runs.breed(run_id, 0, picks, mutation=mutation)
    with pytest.raises(StudioError, match="no generation 5"):
        runs.breed(run_id, 5, [1], mutation=0.1)
    assert len(runs.store.runs()) == before and runs.get(run_id).last == 1


def test_breeding_an_earlier_generation_branches_and_keeps_both(runs: StudioRuns) -> None:
    run_id = runs.create(runs.songs.demo(), seed=4)
    runs.breed(run_id, 0, [2, 5], mutation=0.1)
    runs.breed(run_id, 1, [0, 7], mutation=0.1)
    original = [p.genome for p in runs.store.individuals(run_id, 2)]
    branch, generation = runs.breed(run_id, 1, [0, 7], mutation=0.1)
    assert branch != run_id and generation == 2
    assert runs.get(branch).branch_of == (run_id, 1)
    assert runs.get(run_id).last == 2  # the original run is untouched
    again = [p.genome for p in runs.store.individuals(branch, 2)]
    assert all(np.array_equal(a, b) for a, b in zip(original, again, strict=True))
    copied = runs.store.individuals(branch, 1)
    first = {p.id: p.index for p in runs.store.individuals(branch, 0)}
    mine = {p.id: p.index for p in runs.store.individuals(run_id, 0)}
    assert [[first[q] for q in p.parents] for p in copied] == [
        [mine[q] for q in p.parents] for p in runs.store.individuals(run_id, 1)
    ]
    assert {p.index for p in runs.store.individuals(branch, 0) if p.picked} == {2, 5}


def test_dancing_on_to_another_song_keeps_the_dancers(runs: StudioRuns) -> None:
    run_id = runs.create(runs.songs.demo(), seed=4)
    other = runs.songs.get("demo-sway")
    branch = runs.branch(run_id, 0, song=other)
    assert runs.get(branch).song == other
    old = runs.store.individuals(run_id, 0)
    new = runs.store.individuals(branch, 0)
    assert all(np.array_equal(a.genome, b.genome) for a, b in zip(old, new, strict=True))


def test_a_tempo_correction_reanalyses_the_beats(runs: StudioRuns) -> None:
    run_id = runs.create(runs.songs.demo(), seed=4)
    tempo = runs.music(run_id)[0].tempo_bpm
    runs.set_bpm(run_id, 2 * tempo)
    assert runs.music(run_id)[0].tempo_bpm == pytest.approx(2 * tempo)
    runs.set_bpm(run_id, None)
    assert runs.music(run_id)[0].tempo_bpm == pytest.approx(tempo)
    with pytest.raises(StudioError, match="bpm"):
        runs.set_bpm(run_id, 1000.0)


def test_a_beat_shift_moves_the_beats_and_is_kept(runs: StudioRuns) -> None:
    run_id = runs.create(runs.songs.demo(), seed=4)
    beats = runs.music(run_id)[0].beats
    runs.set_beat_shift(run_id, -0.25)
    assert runs.get(run_id).beat_shift == -0.25
    moved = runs.music(run_id)[0].beats
    interval = np.diff(beats)[0]
    np.testing.assert_allclose(moved[:3], beats[:3] - 0.25 * np.diff(beats)[:3])
    assert 0.2 * interval < beats[1] - moved[1] < 0.3 * interval
    motion = Motion(runs)
    _, trajs = motion.dance_generation(run_id, 0)
    assert trajs[0].beats is not None and np.array_equal(trajs[0].beats, moved)
    runs.set_beat_shift(run_id, None)
    assert runs.get(run_id).beat_shift == 0.0
    assert np.array_equal(runs.music(run_id)[0].beats, beats)
    with pytest.raises(StudioError, match="beat shift"):
        runs.set_beat_shift(run_id, 0.75)


def test_a_generation_pack_holds_every_dancer_in_millimetres(runs: StudioRuns) -> None:
    run_id = runs.create(runs.songs.demo(), seed=4)
    motion = Motion(runs)
    header, arrays = decode_pack(motion.generation(run_id, 0))
    people, trajs = motion.dance_generation(run_id, 0)
    positions = arrays["positions"]
    assert positions.shape == (16, trajs[0].n_frames, 17, 2) and positions.dtype == np.int16
    assert np.abs(positions * header["scale"] - np.stack([t.positions for t in trajs])).max() < 6e-4
    assert [d["id"] for d in header["dancers"]] == [p.id for p in people]
    assert header["fps"] == 60 and header["mutation"] == pytest.approx(0.08)


def test_the_stage_pack_changes_body_genes(runs: StudioRuns) -> None:
    run_id = runs.create(runs.songs.demo(), seed=4)
    person = runs.store.individuals(run_id, 0)[0]
    motion = Motion(runs)
    header, arrays = decode_pack(motion.stage(person.id, {"stiffness": 0.9}))
    assert header["genes"]["stiffness"] == 0.9
    assert arrays["positions"].dtype == np.float32 and arrays["forces"].shape[-1] == 2
    assert arrays["triggers"].shape[1] == len(header["triggerNodes"])
    with pytest.raises(StudioError, match="no slider"):
        motion.stage(person.id, {"hue": 0.5})
    lineage = motion.lineage(person.id)
    assert [p["id"] for p in lineage] == [person.id] and len(lineage[0]["pose"]) == 17


def test_the_live_dancer_is_the_recorded_dance_until_grabbed(runs: StudioRuns) -> None:
    run_id = runs.create(runs.songs.demo(), seed=4)
    person = runs.store.individuals(run_id, 0)[1]
    dancer = Motion(runs).stage_dancer(person.id, {})
    recorded = dancer.dance().positions
    live = LiveDancer(dancer)
    for frame in (1, 2, 40, 41, 500, 30):  # forward, a jump, and a rewind
        live.step_to(frame)
        assert live.frame == frame
        np.testing.assert_array_equal(live.positions, recorded[frame])
    pelvis = list(dancer.dance(1).node_names).index("pelvis")
    start = live.positions[pelvis].copy()
    for frame in range(31, 120):
        live.step_to(frame, Grab(pelvis, (float(start[0]) + 1.0, float(start[1]))))
    assert live.positions[pelvis, 0] - recorded[119, pelvis, 0] > 0.3
    assert not live.state.failed.any()


def test_songs_are_found_by_generated_ids_only(tmp_path: Path, studio_home: None) -> None:
    library = SongLibrary(tmp_path / "songs")
    for bad in ("../studio.db", "u123", "demo-nothing", "/etc/passwd", "ufffffffffffffffff"):
        with pytest.raises(SongError):
            library.get(bad)
    junk = library.incoming()
    junk.write_bytes(b"RIFF....WAVEfmt " + bytes(100))
    with pytest.raises(SongError) as error:
        library.accept(junk, "../../secret/x.wav")
    assert str(error.value).startswith("x.wav: ") and str(tmp_path) not in str(error.value)
    assert not junk.exists()


def test_the_studio_benchmark_runs(studio_home: None) -> None:
    from sinews.benchmarks import studio

    cases = studio.dancer_breeding(scale="quick")
    assert [m.unit for m in cases] == ["generations/s", "encodes/s", "dancer-seconds/MB"]
    assert all(m.ours > 0 and m.reference > 0 for m in cases)
