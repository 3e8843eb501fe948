"""The run store: evolution runs in SQLite (WAL, one transaction per generation).

Tables: ``runs`` (kind, config, seed, song, code version, status),
``individuals`` (genome blob + the run's codec, seed, fitness and terms,
picked and failed flags), ``parents`` (lineage, up to two per child),
``generations`` (the strategy checkpoint) and ``media`` (files, relative to
the database's directory). Nothing here is specific to dancers: any kind of
run stores its genomes through a codec and its own fitness terms.
"""

from __future__ import annotations

from sinews.store.codec import CODECS, decode_genome, encode_genome
from sinews.store.environment import code_version, default_db_path
from sinews.store.errors import StoreError
from sinews.store.export import export_run
from sinews.store.records import GenerationRecord, Individual, Media, RunInfo, ScoreTable
from sinews.store.runs import RunStore
from sinews.store.schema import APPLICATION_ID, SCHEMA_VERSION
from sinews.store.stats import GenerationStats, generation_stats

__all__ = [
    "APPLICATION_ID",
    "CODECS",
    "SCHEMA_VERSION",
    "GenerationRecord",
    "GenerationStats",
    "Individual",
    "Media",
    "RunInfo",
    "RunStore",
    "ScoreTable",
    "StoreError",
    "code_version",
    "decode_genome",
    "default_db_path",
    "encode_genome",
    "export_run",
    "generation_stats",
]
