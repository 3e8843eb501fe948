"""Export a run to plain files anyone can read: JSON, CSV, JSON lines, and its media."""

from __future__ import annotations

import csv
import dataclasses
import json
import os
import shutil
from pathlib import Path

import numpy as np

from sinews.store.errors import StoreError
from sinews.store.runs import RunStore
from sinews.store.stats import generation_stats

__all__ = ["export_run"]


def export_run(store: RunStore, run_id: int, directory: str | os.PathLike[str]) -> list[Path]:
    """Write a run into ``directory`` (created if needed) and return the files written.

    Files: ``run.json`` (the run and its config), ``individuals.csv`` (one
    row per individual: ids, fitness, flags, parents, terms),
    ``genomes.jsonl`` (one JSON object per individual, genome as a list),
    ``generations.csv`` (best and mean fitness, the best's terms) and the
    run's media under ``media/``.

    Raises:
        StoreError: the run does not exist or the directory cannot be written.
    """
    info = store.run(run_id)
    out = Path(directory)
    individuals = store.individuals(run_id)
    names = list(dict.fromkeys(n for ind in individuals for n in (ind.terms or {})))
    written: list[Path] = []
    try:
        out.mkdir(parents=True, exist_ok=True)
        path = out / "run.json"
        path.write_text(json.dumps(dataclasses.asdict(info), indent=1) + "\n")
        written.append(path)
        path = out / "individuals.csv"
        with open(path, "w", newline="") as fh:
            writer = csv.writer(fh)
            writer.writerow(
                ["id", "generation", "index", "seed", "fitness", "failed", "picked", "parents",
                 *names]
            )  # fmt: skip
            for ind in individuals:
                terms = ind.terms or {}
                writer.writerow(
                    [ind.id, ind.generation, ind.index, ind.seed, ind.fitness, int(ind.failed),
                     int(ind.picked), " ".join(map(str, ind.parents)),
                     *(terms.get(n) for n in names)]
                )  # fmt: skip
        written.append(path)
        path = out / "genomes.jsonl"
        with open(path, "w") as fh:
            for ind in individuals:
                genome = ind.genome.tolist() if isinstance(ind.genome, np.ndarray) else ind.genome
                doc = {"id": ind.id, "generation": ind.generation, "index": ind.index}
                fh.write(json.dumps({**doc, "genome": genome}) + "\n")
        written.append(path)
        written.append(_generations_csv(store, run_id, out / "generations.csv"))
        for media in store.media(run_id):
            source = store.root / media.path
            if source.is_file():
                target = out / "media" / source.name
                target.parent.mkdir(exist_ok=True)
                written.append(Path(shutil.copy2(source, target)))
    except OSError as exc:
        raise StoreError(f"{out}: cannot export run {run_id} ({exc.strerror or exc})") from None
    return written


def _generations_csv(store: RunStore, run_id: int, path: Path) -> Path:
    stats = generation_stats(store.scores(run_id))
    with open(path, "w", newline="") as fh:
        writer = csv.writer(fh)
        writer.writerow(["generation", "best", "mean", "failed", *stats.best_terms])
        for k, generation in enumerate(stats.generations):
            terms = [values[k] for values in stats.best_terms.values()]
            writer.writerow([generation, stats.best[k], stats.mean[k], stats.failed[k], *terms])
    return path
