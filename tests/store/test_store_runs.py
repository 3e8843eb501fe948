"""The run store: exact round trips, one transaction per generation, lineage, media, export."""

from __future__ import annotations

import json
import sqlite3
from pathlib import Path

import numpy as np
import pytest

from sinews.store import (
    GenerationRecord,
    RunStore,
    StoreError,
    decode_genome,
    default_db_path,
    encode_genome,
    export_run,
    generation_stats,
)

P, G = 4, 5


def record(generation: int, rng: np.random.Generator, *, parents: np.ndarray | None = None,
           fitness: bool = True) -> GenerationRecord:  # fmt: skip
    if parents is None:
        parents = np.full((P, 2), -1) if generation == 0 else rng.integers(-1, P, (P, 2))
        parents[:, 0] = np.abs(parents[:, 0]) if generation else -1
    return GenerationRecord(
        generation=generation,
        genomes=rng.random((P, G)),
        parents=np.asarray(parents, dtype=np.int64),
        checkpoint=f"state {generation}".encode(),
        seeds=np.arange(P) + 100 * generation,
        fitness=rng.normal(size=P) if fitness else None,
        terms=rng.normal(size=(P, 2)) if fitness else None,
        term_names=("a", "b"),
        failed=np.array([False, True, False, False]),
    )


@pytest.fixture
def store(tmp_path: Path) -> RunStore:
    return RunStore(tmp_path / "runs.db")


def new_run(store: RunStore, codec: str = "float64") -> int:
    return store.create_run("test", config={"generations": 3}, seed=7, genome_codec=codec)


def test_generations_round_trip_exactly(store: RunStore) -> None:
    run = new_run(store)
    rng = np.random.default_rng(0)
    written = [record(g, rng) for g in range(3)]
    for rec in written:
        store.add_generation(run, rec)
    assert store.last_generation(run) == 2
    best = -np.inf
    for rec in written:
        assert rec.fitness is not None and rec.seeds is not None and rec.terms is not None
        got = store.individuals(run, rec.generation)
        np.testing.assert_array_equal([i.genome for i in got], rec.genomes)
        assert [i.fitness for i in got] == list(rec.fitness)
        assert [i.seed for i in got] == list(rec.seeds)
        assert [i.failed for i in got] == [False, True, False, False]
        assert got[0].terms == {"a": rec.terms[0, 0], "b": rec.terms[0, 1]}
        assert store.checkpoint(run, rec.generation) == rec.checkpoint
        np.testing.assert_array_equal(store.generation_fitness(run, rec.generation), rec.fitness)
        best = max(best, float(rec.fitness.max()))
    info = store.run(run)
    assert (info.kind, info.seed, info.status, info.generations) == ("test", 7, "running", 3)
    assert info.best_fitness == best


def test_generations_must_come_in_order(store: RunStore) -> None:
    run = new_run(store)
    rng = np.random.default_rng(1)
    with pytest.raises(StoreError, match="expected generation 0, got 1"):
        store.add_generation(run, record(1, rng))
    store.add_generation(run, record(0, rng))
    with pytest.raises(StoreError, match="expected generation 1, got 0"):
        store.add_generation(run, record(0, rng))


def test_a_failed_generation_leaves_nothing_behind(store: RunStore) -> None:
    run = new_run(store)
    rng = np.random.default_rng(2)
    store.add_generation(run, record(0, rng))
    bad_parents = np.array([[0, -1], [1, -1], [2, -1], [P + 3, -1]])  # the last parent is missing
    with pytest.raises(StoreError, match="no individual 7 in the previous generation"):
        store.add_generation(run, record(1, rng, parents=bad_parents))
    assert store.last_generation(run) == 0
    assert len(store.individuals(run)) == P


def test_lineage_walks_back_to_generation_zero(store: RunStore) -> None:
    run = new_run(store)
    rng = np.random.default_rng(3)
    store.add_generation(run, record(0, rng))
    store.add_generation(run, record(1, rng, parents=np.array([[0, 1], [2, -1], [3, -1], [3, 2]])))
    store.add_generation(run, record(2, rng, parents=np.array([[0, 3], [1, -1], [1, -1], [2, -1]])))
    child = store.individuals(run, 2)[0]
    ancestors = store.lineage(child.id)
    assert [(a.generation, a.index) for a in ancestors] == [
        (2, 0), (1, 0), (1, 3), (0, 0), (0, 1), (0, 2), (0, 3)
    ]  # fmt: skip
    by_id = {a.id: a for a in ancestors}
    assert [by_id[p].index for p in child.parents] == [0, 3]
    assert all(by_id[p].generation == a.generation - 1 for a in ancestors for p in a.parents)
    with pytest.raises(StoreError, match="no individual 999"):
        store.lineage(999)


def test_picks_are_marked_with_the_next_generation(store: RunStore) -> None:
    run = new_run(store)
    rng = np.random.default_rng(4)
    store.add_generation(run, record(0, rng, fitness=False))
    assert store.generation_fitness(run, 0) is None
    store.add_generation(run, record(1, rng, fitness=False), picks=[1, 3])
    assert [i.picked for i in store.individuals(run, 0)] == [False, True, False, True]


@pytest.mark.parametrize("codec", ["float64", "float32", "json"])
def test_codecs_round_trip_exactly(codec: str) -> None:
    genome = (
        {"tree": ["+", 1.5, ["x"]]}
        if codec == "json"
        else np.array([0.1, 0.7, 1.0], dtype=np.float32)
    )
    blob = encode_genome(genome, codec)
    decoded = decode_genome(blob, codec)
    if codec == "json":
        assert decoded == genome
    else:
        np.testing.assert_array_equal(decoded, genome)


def test_codecs_refuse_what_they_cannot_hold() -> None:
    with pytest.raises(StoreError, match="float32 cannot hold exactly"):
        encode_genome(np.array([0.1]), "float32")
    with pytest.raises(StoreError, match="flat vector"):
        encode_genome(np.zeros((2, 2)), "float64")
    with pytest.raises(StoreError, match="unknown genome codec"):
        encode_genome([1.0], "bson")
    with pytest.raises(StoreError, match="truncated"):
        decode_genome(b"\x00" * 5, "float64")


def test_generic_runs_store_json_genomes(store: RunStore) -> None:
    run = new_run(store, codec="json")
    trees = [["+", "x", float(k)] for k in range(P)]
    rec = record(0, np.random.default_rng(5))
    store.add_generation(run, GenerationRecord(generation=0, genomes=trees, parents=rec.parents,
                                               checkpoint=b"gp"))  # fmt: skip
    assert [i.genome for i in store.individuals(run)] == trees
    assert store.individuals(run)[0].fitness is None


def test_best_status_media_and_stats(store: RunStore, tmp_path: Path) -> None:
    run = new_run(store)
    rng = np.random.default_rng(6)
    for g in range(2):
        store.add_generation(run, record(g, rng))
    best = store.best(run)
    assert best.fitness == max(i.fitness for i in store.individuals(run) if i.fitness is not None)
    store.set_status(run, "finished")
    assert store.run(run).status == "finished"
    with pytest.raises(StoreError, match="status must be"):
        store.set_status(run, "paused")
    video = tmp_path / "media" / "best.mp4"
    video.parent.mkdir()
    video.write_bytes(b"video")
    store.add_media(run, video, kind="mp4", individual_id=best.id)
    (media,) = store.media(run)
    assert media.path == "media/best.mp4" and media.individual_id == best.id
    stats = generation_stats(store.scores(run))
    assert stats.generations.tolist() == [0, 1] and stats.failed.tolist() == [1, 1]
    scores = store.scores(run)
    first = scores.fitness[:P]
    assert stats.best[0] == first.max()
    assert stats.mean[0] == pytest.approx(first[[0, 2, 3]].mean())
    assert stats.best_terms["a"][0] == scores.terms[int(np.argmax(first))]["a"]
    later = store.scores(run, since=1)
    assert later.generation.tolist() == [1] * P
    np.testing.assert_array_equal(later.fitness, scores.fitness[P:])


def test_export_writes_plain_files(store: RunStore, tmp_path: Path) -> None:
    run = new_run(store)
    rng = np.random.default_rng(7)
    for g in range(2):
        store.add_generation(run, record(g, rng))
    files = export_run(store, run, tmp_path / "out")
    assert {f.name for f in files} == {
        "run.json", "individuals.csv", "genomes.jsonl", "generations.csv"
    }  # fmt: skip
    assert json.loads((tmp_path / "out" / "run.json").read_text())["id"] == run
    lines = (tmp_path / "out" / "genomes.jsonl").read_text().splitlines()
    first = json.loads(lines[0])
    assert len(lines) == 2 * P
    assert first["genome"] == store.individuals(run, 0)[0].genome.tolist()
    header = (tmp_path / "out" / "individuals.csv").read_text().splitlines()[0]
    assert header.endswith("parents,a,b")


def test_missing_things_are_reported(store: RunStore) -> None:
    with pytest.raises(StoreError, match="no run 5"):
        store.run(5)
    run = new_run(store)
    with pytest.raises(StoreError, match="no scored individuals"):
        store.best(run)
    with pytest.raises(StoreError, match="has no generation 0"):
        store.checkpoint(run, 0)


@pytest.mark.parametrize(("sql", "value", "message"), [
    ("UPDATE runs SET config = ?", '{"generations": 3', "config of run 1 .*not readable JSON"),
    ("UPDATE runs SET config = ?", "[" * 100_000 + "]" * 100_000, "not readable JSON"),
    ("UPDATE runs SET config = ?", "[3]", "config of run 1 .*not an object"),
    ("UPDATE individuals SET terms = ?", '{"a": "far"}', "terms .*not names and numbers"),
    ("UPDATE individuals SET terms = ?", '{"a": ' + "9" * 5000 + "}", "terms .*not readable"),
    ("UPDATE individuals SET genome = ?", b"\xff[1,", "genome .*not readable JSON"),
])  # fmt: skip
def test_a_tampered_row_is_a_store_error(tmp_path: Path, sql: str, value: str | bytes,
                                         message: str) -> None:  # fmt: skip
    path = tmp_path / "runs.db"
    with RunStore(path) as store:
        run = new_run(store, codec="json")
        rec = record(0, np.random.default_rng(5))
        store.add_generation(run, GenerationRecord(
            generation=0, genomes=[[1.0]] * P, parents=rec.parents, checkpoint=b"gp",
            fitness=rec.fitness, terms=rec.terms, term_names=rec.term_names))  # fmt: skip
    with sqlite3.connect(path) as conn:
        conn.execute(sql, (value,))
    with RunStore(path) as store, pytest.raises(StoreError, match=message):
        store.run(run)
        store.individuals(run)
        store.scores(run)


def test_database_is_in_wal_mode_with_our_ids(store: RunStore) -> None:
    new_run(store)
    store.close()
    conn = sqlite3.connect(store.path)
    assert conn.execute("PRAGMA journal_mode").fetchone()[0] == "wal"
    assert conn.execute("PRAGMA application_id").fetchone()[0] == 0x53494E57
    assert conn.execute("PRAGMA user_version").fetchone()[0] == 1
    conn.close()


def test_default_location_follows_the_data_dir(monkeypatch: pytest.MonkeyPatch,
                                                tmp_path: Path) -> None:  # fmt: skip
    monkeypatch.setenv("XDG_DATA_HOME", str(tmp_path))
    assert default_db_path() == tmp_path / "sinews" / "sinews.db"


def test_a_branch_copies_generations_lineage_and_checkpoints_in_one_go(store: RunStore) -> None:
    run = new_run(store)
    rng = np.random.default_rng(5)
    store.add_generation(run, record(0, rng))
    store.add_generation(run, record(1, rng), picks=[1, 2])
    store.add_generation(run, record(2, rng), picks=[0])
    branch = store.branch(run, 1, config={"generations": 3, "branch_of": [run, 1]})
    assert store.run(branch).generations == 2 and store.run(branch).config["branch_of"] == [run, 1]
    for generation in (0, 1):
        ours, theirs = store.individuals(run, generation), store.individuals(branch, generation)
        assert store.checkpoint(branch, generation) == store.checkpoint(run, generation)
        index_of = {p.id: p.index for p in store.individuals(run)}
        copy_of = {p.id: p.index for p in store.individuals(branch)}
        for a, b in zip(ours, theirs, strict=True):
            np.testing.assert_array_equal(a.genome, b.genome)
            assert (a.seed, a.fitness, a.terms, a.failed) == (b.seed, b.fitness, b.terms, b.failed)
            assert [index_of[p] for p in a.parents] == [copy_of[p] for p in b.parents]
            assert all(p in copy_of for p in b.parents)  # the copies' parents are copies
    # picks that bred a copied generation are copied; those made in the last copy are not
    assert [p.picked for p in store.individuals(branch, 0)] == [False, True, True, False]
    assert not any(p.picked for p in store.individuals(branch, 1))
    with pytest.raises(StoreError, match="no generation 3"):
        store.branch(run, 3, config={})


def test_a_branch_that_fails_midway_leaves_no_run_behind(store: RunStore) -> None:
    run = new_run(store)
    rng = np.random.default_rng(6)
    store.add_generation(run, record(0, rng))
    store.add_generation(run, record(1, rng))
    before = (len(store.runs()), len(store.individuals(run)))
    # the last statement of the copy fails, after the run, individuals and parents are in
    store._conn.execute(
        "CREATE TEMP TRIGGER fail BEFORE INSERT ON generations WHEN NEW.run_id <> "
        f"{run} BEGIN SELECT RAISE(ABORT, 'disk gone'); END"
    )
    with pytest.raises(StoreError, match="disk gone"):
        store.branch(run, 1, config={})
    total = store._conn.execute("SELECT count(*) FROM individuals").fetchone()[0]
    assert (len(store.runs()), total) == before
