"""What the store reads and writes: runs, generations, individuals, media."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

__all__ = ["RUN_STATUSES", "GenerationRecord", "Individual", "Media", "RunInfo", "ScoreTable"]

RUN_STATUSES = ("running", "finished", "failed")


@dataclass(frozen=True)
class RunInfo:
    """One evolution run.

    Attributes:
        id: the run's number.
        kind: what evolves, e.g. ``"dancers"``; it decides how to resume and render.
        config: the run's settings (JSON object) — enough to continue it.
        seed: the run seed every random stream derives from.
        song_hash: SHA-256 of the song, for runs with music.
        song_path: where the song was (absolute path), for runs with music.
        code_version: the sinews version that started the run.
        genome_codec: how its genomes are stored (see `sinews.store.codec`).
        status: ``"running"``, ``"finished"`` or ``"failed"``.
        created: ISO 8601 UTC time the run started.
        updated: ISO 8601 UTC time of its last change.
        generations: number of generations stored.
        best_fitness: best fitness over all generations (None if none scored).
    """

    id: int
    kind: str
    config: dict[str, Any]
    seed: int
    song_hash: str | None
    song_path: str | None
    code_version: str
    genome_codec: str
    status: str
    created: str
    updated: str
    generations: int
    best_fitness: float | None


@dataclass(frozen=True)
class Individual:
    """One member of one generation.

    Attributes:
        id: unique over the database (what ``runs lineage`` takes).
        run_id: its run.
        generation: its generation (0 = the random start).
        index: its place in the generation, 0 .. P-1.
        genome: decoded genome ((G,) float64 array, or a JSON value).
        seed: its simulation seed, if the kind has one.
        fitness: total fitness (higher is better; -inf for a failed
            simulation), or None if not scored.
        terms: each fitness term's value (None for a term that was NaN).
        picked: a person picked it.
        failed: its simulation failed.
        parents: ids of its parents (0, 1 or 2) in the previous generation.
    """

    id: int
    run_id: int
    generation: int
    index: int
    genome: Any
    seed: int | None
    fitness: float | None
    terms: dict[str, float | None] | None
    picked: bool
    failed: bool
    parents: tuple[int, ...]


@dataclass(frozen=True)
class GenerationRecord:
    """A whole generation, written in one transaction.

    Attributes:
        generation: its number (must follow the last stored one).
        genomes: (P, G) array, or P JSON values for the ``json`` codec.
        parents: (P, 2) indices into the previous generation, -1 for none.
        checkpoint: the strategy's state when it asked for this generation
            (`sinews.evolve.Strategy.to_bytes`).
        seeds: (P,) simulation seeds, or None.
        fitness: (P,) totals, or None when not scored (e.g. interactive runs).
        terms: (P, K) term values with ``term_names`` as columns, or None.
        term_names: (K,) names of the columns of ``terms``.
        failed: (P,) True where the simulation failed, or None.
    """

    generation: int
    genomes: npt.NDArray[np.float64] | Sequence[Any]
    parents: npt.NDArray[np.int64]
    checkpoint: bytes
    seeds: npt.NDArray[np.int64] | None = None
    fitness: npt.NDArray[np.float64] | None = None
    terms: npt.NDArray[np.float64] | None = None
    term_names: Sequence[str] = ()
    failed: npt.NDArray[np.bool_] | None = None

    def term_dicts(self) -> list[Mapping[str, float | None]] | None:
        """One ``{name: value}`` per individual, NaN/inf as None (JSON-safe)."""
        if self.terms is None:
            return None
        return [
            {
                name: float(v) if np.isfinite(v) else None
                for name, v in zip(self.term_names, row, strict=True)
            }
            for row in self.terms
        ]


@dataclass(frozen=True)
class Media:
    """A file made from a run (a video, a picture, a trajectory).

    Attributes:
        id: the media's number.
        run_id: its run.
        individual_id: the individual shown, or None for a whole-run file (a plot).
        kind: e.g. ``"mp4"``, ``"png"``, ``"trajectory"``.
        path: path relative to the database's directory.
        created: ISO 8601 UTC time.
    """

    id: int
    run_id: int
    individual_id: int | None
    kind: str
    path: str
    created: str


@dataclass(frozen=True, eq=False)
class ScoreTable:
    """The scores of a run's scored individuals, by generation then index (n rows).

    Attributes:
        generation: (n,) int64.
        index: (n,) int64 place in the generation.
        fitness: (n,) float64 totals (-inf for failed).
        failed: (n,) bool.
        terms: n dicts of term values (None for NaN).
    """

    generation: npt.NDArray[np.int64]
    index: npt.NDArray[np.int64]
    fitness: npt.NDArray[np.float64]
    failed: npt.NDArray[np.bool_]
    terms: list[dict[str, float | None]]
