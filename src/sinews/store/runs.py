"""`RunStore`: evolution runs in one SQLite file, one transaction per generation.

A generation is written whole or not at all (its individuals, their
parents, fitness and terms, the strategy checkpoint, and any picks a person
made in the generation before), so a run killed at any moment leaves the
last complete generation behind and resumes from it.
"""

from __future__ import annotations

import json
import os
import sqlite3
from collections.abc import Iterator, Mapping, Sequence
from contextlib import contextmanager
from datetime import UTC, datetime
from pathlib import Path
from types import TracebackType
from typing import Any

import numpy as np
import numpy.typing as npt

from sinews.limits import MAX_RUN_ID
from sinews.store.codec import CODECS, decode_genome, encode_genome, stored_json
from sinews.store.environment import code_version, default_db_path
from sinews.store.errors import StoreError
from sinews.store.records import (
    RUN_STATUSES,
    GenerationRecord,
    Individual,
    Media,
    RunInfo,
    ScoreTable,
)
from sinews.store.schema import connect, hold, release

__all__ = ["RunStore"]

_RUN_COLUMNS = (
    "id, kind, config, seed, song_hash, song_path, code_version, genome_codec, status, "
    "created, updated, "
    "(SELECT count(*) FROM generations g WHERE g.run_id = runs.id), "
    "(SELECT max(fitness) FROM individuals i WHERE i.run_id = runs.id)"
)
_INDIVIDUAL_COLUMNS = (
    "i.id, i.run_id, i.generation, i.idx, i.genome, i.seed, i.fitness, i.terms, i.picked, "
    "i.failed, r.genome_codec, "
    "(SELECT group_concat(parent) FROM (SELECT parent FROM parents p "
    "WHERE p.child = i.id ORDER BY slot))"
)


def _now() -> str:
    return datetime.now(UTC).isoformat(timespec="seconds")


class RunStore:
    """The runs database.

    Args:
        path: the SQLite file (created if missing); default `default_db_path`.
        readonly: open only to read (nothing created or written; see `connect`).

    Raises:
        StoreError: a corrupt, foreign or newer database (see `sinews.store.schema`).
    """

    def __init__(
        self, path: str | os.PathLike[str] | None = None, *, readonly: bool = False
    ) -> None:
        self.path = Path(path) if path is not None else default_db_path()
        self._conn = connect(self.path, readonly=readonly)
        hold(self.path)
        self._held = True

    @property
    def root(self) -> Path:
        """The database's directory; media paths are relative to it."""
        return self.path.resolve().parent

    def close(self) -> None:
        """Close the connection."""
        self._conn.close()
        if self._held:
            release(self.path)
            self._held = False

    def __enter__(self) -> RunStore:
        return self

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        self.close()

    @contextmanager
    def _transaction(self) -> Iterator[sqlite3.Connection]:
        """One write transaction (taken at once, so concurrent writers queue)."""
        with self._errors():
            self._conn.execute("BEGIN IMMEDIATE")
            try:
                yield self._conn
            except BaseException:
                self._conn.execute("ROLLBACK")
                raise
            self._conn.execute("COMMIT")

    @contextmanager
    def _errors(self) -> Iterator[None]:
        """Turn SQLite failures (corruption found late, a full disk…) into one-line errors."""
        try:
            yield
        except sqlite3.DatabaseError as exc:
            raise StoreError(f"{self.path}: database error ({exc})") from None

    def _query(self, sql: str, args: Sequence[Any] = ()) -> list[tuple[Any, ...]]:
        """Rows of a read; an id beyond SQLite's integers matches nothing."""
        if any(isinstance(a, int) and not -MAX_RUN_ID - 1 <= a <= MAX_RUN_ID for a in args):
            return []
        with self._errors():
            return self._conn.execute(sql, args).fetchall()

    # -- runs ----------------------------------------------------------------------

    def create_run(
        self,
        kind: str,
        *,
        config: dict[str, Any],
        seed: int,
        genome_codec: str,
        song_hash: str | None = None,
        song_path: str | None = None,
    ) -> int:
        """Start a run (status ``running``) and return its id."""
        if genome_codec not in CODECS:
            raise StoreError(f"unknown genome codec {genome_codec!r}")
        now = _now()
        with self._transaction() as conn:
            cursor = conn.execute(
                "INSERT INTO runs (kind, config, seed, song_hash, song_path, code_version, "
                "genome_codec, status, created, updated) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?)",
                (kind, json.dumps(config), seed, song_hash, song_path, code_version(),
                 genome_codec, "running", now, now),
            )  # fmt: skip
        assert cursor.lastrowid is not None
        return cursor.lastrowid

    def branch(
        self,
        run_id: int,
        generation: int,
        *,
        config: dict[str, Any],
        song_hash: str | None = None,
        song_path: str | None = None,
    ) -> int:
        """A new run holding copies of generations 0..``generation`` of ``run_id``, made in
        one transaction (a crash leaves either no branch or the whole of it).

        The copies keep their genomes, seeds, fitness, terms, lineage (parents are the
        copies) and strategy checkpoints, and the picks that bred the copied
        generations; the picks made in ``generation`` itself are the branch's to make.

        Args:
            run_id: the run to branch from.
            generation: the last generation to copy.
            config: the branch's settings (the caller adds e.g. ``branch_of``).
            song_hash: the branch's song hash (default: the run's).
            song_path: the branch's song file (default: the run's).

        Returns:
            The branch's id (status ``running``).
        """
        info = self.run(run_id)
        if not 0 <= generation < info.generations:
            raise StoreError(f"run {run_id} has no generation {generation}")
        now = _now()
        with self._transaction() as conn:
            cursor = conn.execute(
                "INSERT INTO runs (kind, config, seed, song_hash, song_path, code_version, "
                "genome_codec, status, created, updated) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?)",
                (info.kind, json.dumps(config), info.seed, song_hash or info.song_hash,
                 song_path or info.song_path, code_version(), info.genome_codec, "running",
                 now, now),
            )  # fmt: skip
            new_id = cursor.lastrowid
            conn.execute(
                "INSERT INTO individuals (run_id, generation, idx, genome, seed, fitness, terms, "
                "picked, failed) SELECT ?, generation, idx, genome, seed, fitness, terms, "
                "CASE WHEN generation < ? THEN picked ELSE 0 END, failed FROM individuals "
                "WHERE run_id = ? AND generation <= ? ORDER BY generation, idx",
                (new_id, generation, run_id, generation),
            )
            conn.execute(
                "INSERT INTO parents (child, slot, parent) "
                "SELECT nc.id, p.slot, np.id FROM parents p "
                "JOIN individuals oc ON oc.id = p.child JOIN individuals op ON op.id = p.parent "
                "JOIN individuals nc ON nc.run_id = ? AND nc.generation = oc.generation "
                "AND nc.idx = oc.idx "
                "JOIN individuals np ON np.run_id = ? AND np.generation = op.generation "
                "AND np.idx = op.idx "
                "WHERE oc.run_id = ? AND oc.generation <= ?",
                (new_id, new_id, run_id, generation),
            )
            conn.execute(
                "INSERT INTO generations (run_id, generation, checkpoint, created) "
                "SELECT ?, generation, checkpoint, ? FROM generations "
                "WHERE run_id = ? AND generation <= ? ORDER BY generation",
                (new_id, now, run_id, generation),
            )
        assert new_id is not None
        return new_id

    def run(self, run_id: int) -> RunInfo:
        """The run ``run_id``; `StoreError` if there is none."""
        rows = self._query(f"SELECT {_RUN_COLUMNS} FROM runs WHERE id = ?", (run_id,))
        if not rows:
            raise StoreError(f"no run {run_id} in {self.path}")
        return _run_info(rows[0])

    def runs(self) -> list[RunInfo]:
        """Every run, oldest first."""
        return [
            _run_info(row) for row in self._query(f"SELECT {_RUN_COLUMNS} FROM runs ORDER BY id")
        ]

    def set_status(self, run_id: int, status: str) -> None:
        """Mark a run ``running``, ``finished`` or ``failed``."""
        if status not in RUN_STATUSES:
            raise StoreError(f"status must be one of {', '.join(RUN_STATUSES)}")
        with self._transaction() as conn:
            conn.execute(
                "UPDATE runs SET status = ?, updated = ? WHERE id = ?", (status, _now(), run_id)
            )

    def update_config(self, run_id: int, config: dict[str, Any]) -> None:
        """Replace a run's settings (e.g. more generations when it is extended)."""
        with self._transaction() as conn:
            conn.execute(
                "UPDATE runs SET config = ?, updated = ? WHERE id = ?",
                (json.dumps(config), _now(), run_id),
            )

    # -- generations ---------------------------------------------------------------

    def last_generation(self, run_id: int) -> int:
        """Number of the last stored generation of the run (-1 if none)."""
        rows = self._query("SELECT max(generation) FROM generations WHERE run_id = ?", (run_id,))
        return -1 if rows[0][0] is None else int(rows[0][0])

    def restarts(self, run_id: int) -> list[int]:
        """The generations after 0 made at random, with no parents (a run's restarts)."""
        rows = self._query(
            "SELECT i.generation FROM individuals i LEFT JOIN parents p ON p.child = i.id "
            "WHERE i.run_id = ? AND i.generation > 0 GROUP BY i.generation "
            "HAVING count(p.parent) = 0 ORDER BY i.generation",
            (run_id,),
        )
        return [int(r[0]) for r in rows]

    def checkpoint(self, run_id: int, generation: int) -> bytes:
        """The strategy checkpoint stored with a generation."""
        rows = self._query(
            "SELECT checkpoint FROM generations WHERE run_id = ? AND generation = ?",
            (run_id, generation),
        )
        if not rows:
            raise StoreError(f"run {run_id} has no generation {generation}")
        return bytes(rows[0][0])

    def generation_fitness(self, run_id: int, generation: int) -> npt.NDArray[np.float64] | None:
        """(P,) the stored fitness of a generation by index, or None if it was not scored."""
        rows = self._query(
            "SELECT fitness FROM individuals WHERE run_id = ? AND generation = ? ORDER BY idx",
            (run_id, generation),
        )
        if not rows or any(r[0] is None for r in rows):
            return None
        return np.array([r[0] for r in rows], dtype=np.float64)

    def add_generation(
        self, run_id: int, record: GenerationRecord, *, picks: npt.ArrayLike = ()
    ) -> None:
        """Write a generation in one transaction.

        Args:
            run_id: the run.
            record: the generation; its number must follow the last stored one.
            picks: indices (in the previous generation) a person picked, marked
                in the same transaction.

        Raises:
            StoreError: the generation is out of sequence (e.g. another process
                is continuing the same run) or the arrays do not match.
        """
        info = self.run(run_id)
        size = len(record.genomes)
        blobs = [encode_genome(g, info.genome_codec) for g in record.genomes]
        if record.parents.shape != (size, 2):
            raise StoreError(f"parents must have shape ({size}, 2), got {record.parents.shape}")
        seeds = _column(record.seeds, size, int)
        fitness = _column(record.fitness, size, float)
        failed = _column(record.failed, size, bool)
        terms: Sequence[Mapping[str, float | None] | None] = record.term_dicts() or [None] * size
        g = record.generation
        with self._transaction() as conn:
            last = conn.execute(
                "SELECT max(generation) FROM generations WHERE run_id = ?", (run_id,)
            ).fetchone()[0]
            expected = 0 if last is None else last + 1
            if g != expected:
                raise StoreError(f"run {run_id}: expected generation {expected}, got {g}")
            conn.executemany(
                "INSERT INTO individuals (run_id, generation, idx, genome, seed, fitness, terms, "
                "failed) VALUES (?, ?, ?, ?, ?, ?, ?, ?)",
                [
                    (run_id, g, k, blobs[k], seeds[k], fitness[k],
                     None if terms[k] is None else json.dumps(terms[k]), bool(failed[k]))
                    for k in range(size)
                ],
            )  # fmt: skip
            ids = _ids_by_index(conn, run_id, g)
            previous = _ids_by_index(conn, run_id, g - 1) if g > 0 else {}
            conn.executemany(
                "UPDATE individuals SET picked = 1 WHERE id = ?",
                [(_parent_id(previous, int(k)),) for k in np.asarray(picks, dtype=np.int64)],
            )
            conn.executemany(
                "INSERT INTO parents (child, slot, parent) VALUES (?, ?, ?)",
                [
                    (ids[k], slot, _parent_id(previous, int(p)))
                    for k in range(size)
                    for slot, p in enumerate(record.parents[k])
                    if p >= 0
                ],
            )
            conn.execute(
                "INSERT INTO generations (run_id, generation, checkpoint, created) "
                "VALUES (?, ?, ?, ?)",
                (run_id, g, record.checkpoint, _now()),
            )
            conn.execute("UPDATE runs SET updated = ? WHERE id = ?", (_now(), run_id))

    # -- individuals ---------------------------------------------------------------

    def individuals(self, run_id: int, generation: int | None = None) -> list[Individual]:
        """A run's individuals (all, or one generation), by generation then index."""
        where, args = "i.run_id = ?", [run_id]
        if generation is not None:
            where, args = where + " AND i.generation = ?", [run_id, generation]
        return self._individuals(where, args)

    def individual(self, individual_id: int) -> Individual:
        """One individual by id; `StoreError` if there is none."""
        found = self._individuals("i.id = ?", [individual_id])
        if not found:
            raise StoreError(f"no individual {individual_id} in {self.path}")
        return found[0]

    def best(self, run_id: int) -> Individual:
        """The fittest individual of the run (the earliest on ties)."""
        self.run(run_id)
        rows = self._query(
            "SELECT id FROM individuals WHERE run_id = ? AND fitness IS NOT NULL "
            "ORDER BY fitness DESC, generation, idx LIMIT 1",
            (run_id,),
        )
        if not rows:
            raise StoreError(f"run {run_id} has no scored individuals")
        return self.individual(int(rows[0][0]))

    def picks(self, run_id: int) -> list[Individual]:
        """The individuals a person picked, oldest generation first (empty if none)."""
        return self._individuals(
            "i.run_id = ? AND i.picked = 1", [run_id], order="i.generation, i.idx"
        )

    def lineage(self, individual_id: int) -> list[Individual]:
        """The individual and all its ancestors (recursive CTE), newest generation first."""
        self.individual(individual_id)
        return self._individuals(
            "i.id IN (WITH RECURSIVE ancestors(id) AS (SELECT ? UNION "
            "SELECT p.parent FROM parents p JOIN ancestors a ON p.child = a.id) "
            "SELECT id FROM ancestors)",
            [individual_id],
            order="i.generation DESC, i.idx",
        )

    def scores(self, run_id: int, *, since: int = 0) -> ScoreTable:
        """Every scored individual's fitness, terms and failed flag (for stats and plots),
        of the generations from ``since`` on."""
        rows = self._query(
            "SELECT generation, idx, fitness, failed, terms FROM individuals WHERE run_id = ? "
            "AND generation >= ? AND fitness IS NOT NULL ORDER BY generation, idx",
            (run_id, since),
        )
        return ScoreTable(
            generation=np.array([r[0] for r in rows], dtype=np.int64),
            index=np.array([r[1] for r in rows], dtype=np.int64),
            fitness=np.array([r[2] for r in rows], dtype=np.float64),
            failed=np.array([bool(r[3]) for r in rows], dtype=bool),
            terms=[_terms(r[4]) if r[4] else {} for r in rows],
        )

    def _individuals(self, where: str, args: Sequence[Any], order: str = "") -> list[Individual]:
        rows = self._query(
            f"SELECT {_INDIVIDUAL_COLUMNS} FROM individuals i JOIN runs r ON r.id = i.run_id "
            f"WHERE {where} ORDER BY {order or 'i.generation, i.idx'}",
            args,
        )
        return [
            Individual(
                id=row[0],
                run_id=row[1],
                generation=row[2],
                index=row[3],
                genome=decode_genome(row[4], row[10]),
                seed=row[5],
                fitness=row[6],
                terms=None if row[7] is None else _terms(row[7]),
                picked=bool(row[8]),
                failed=bool(row[9]),
                parents=tuple(int(p) for p in row[11].split(",")) if row[11] else (),
            )
            for row in rows
        ]

    # -- media -------------------------------------------------------------------

    def add_media(
        self,
        run_id: int,
        path: str | os.PathLike[str],
        *,
        kind: str,
        individual_id: int | None = None,
    ) -> int:
        """Record a file made from a run (once: the id of an existing record is returned).

        Its path is stored relative to `root`.
        """
        relative = os.path.relpath(Path(path).resolve(), self.root)
        with self._transaction() as conn:
            known = conn.execute(
                "SELECT id FROM media WHERE run_id = ? AND path = ?", (run_id, relative)
            ).fetchone()
            if known is not None:
                return int(known[0])
            cursor = conn.execute(
                "INSERT INTO media (run_id, individual_id, kind, path, created) "
                "VALUES (?, ?, ?, ?, ?)",
                (run_id, individual_id, kind, relative, _now()),
            )
        assert cursor.lastrowid is not None
        return cursor.lastrowid

    def media(self, run_id: int) -> list[Media]:
        """The files recorded for a run, oldest first."""
        rows = self._query(
            "SELECT id, run_id, individual_id, kind, path, created FROM media "
            "WHERE run_id = ? ORDER BY id",
            (run_id,),
        )
        return [Media(*row) for row in rows]


def _run_info(row: tuple[Any, ...]) -> RunInfo:
    values = list(row)
    values[2] = stored_json(values[2], f"config of run {values[0]}")
    if not isinstance(values[2], dict):
        raise StoreError(f"malformed config of run {values[0]} in the database (not an object)")
    return RunInfo(*values)


def _terms(text: str) -> dict[str, float | None]:
    """An individual's stored fitness terms: name -> value (None: not measured)."""
    terms = stored_json(text, "fitness terms")
    try:
        return {str(k): None if v is None else float(v) for k, v in terms.items()}
    except (AttributeError, TypeError, ValueError):
        raise StoreError(
            "malformed fitness terms in the database (not names and numbers)"
        ) from None


def _column(values: npt.ArrayLike | None, size: int, kind: type) -> list[Any]:
    if values is None:
        return [None] * size
    array = np.asarray(values)
    if array.shape != (size,):
        raise StoreError(f"expected one value per individual ({size}), got shape {array.shape}")
    return [kind(v) for v in array.tolist()]


def _ids_by_index(conn: sqlite3.Connection, run_id: int, generation: int) -> dict[int, int]:
    rows = conn.execute(
        "SELECT idx, id FROM individuals WHERE run_id = ? AND generation = ?", (run_id, generation)
    ).fetchall()
    return dict(rows)


def _parent_id(previous: dict[int, int], index: int) -> int:
    if index not in previous:
        raise StoreError(f"no individual {index} in the previous generation")
    return previous[index]
