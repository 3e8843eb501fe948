"""Files made from a stored run, the same whoever asks: a genome file and the fitness plot.

``sinews runs best`` and ``sinews plot`` write them, and so does the figure
page's export buttons (`sinews.studio.figure_exports`), so the page and the
CLI hand out the same files.
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import numpy.typing as npt

from sinews.errors import SinewsError
from sinews.experiments.evolution import full_weight_bests
from sinews.experiments.kinds import kind_of
from sinews.experiments.run_config import EvolutionConfig
from sinews.store import Individual, RunInfo, RunStore, generation_stats

__all__ = ["DANCE_LABEL", "FitnessPlot", "fitness_label", "fitness_plot", "genome_file"]

DANCE_LABEL = "fitness (beat lift + style)"
"""What a figure dance's fitness is (GP and spring-net dances alike), for plots."""


def genome_file(store: RunStore, individual: Individual, *, text: bool = False) -> str:
    """A stored individual's genome file: its genome or controller as JSON, or with ``text``
    a GP program's S-expression (`SinewsError` for kinds without a text form)."""
    kind = kind_of(store.run(individual.run_id))
    if text:
        found = kind.genome_text(individual)
        if found is None:
            raise SinewsError(f"run {individual.run_id}'s genomes have no text form; write a .json")
        return found + "\n"
    return json.dumps(kind.genome_document(store, individual), indent=1) + "\n"


@dataclass(frozen=True)
class FitnessPlot:
    """A run's fitness plot, read from the store (`fitness_plot`), to draw anywhere.

    Attributes:
        generations: (G,) scored generations.
        series: name → (G,) values: best, mean, each best's weighed terms, the best at full
            style weight.
        title: the plot's title.
        marks: label → generation where style starts and where it is full, and where the
            run restarted.
    """

    generations: npt.NDArray[np.int64]
    series: dict[str, npt.NDArray[np.float64]]
    title: str
    marks: dict[str, float]

    def draw(self, path: str | os.PathLike[str]) -> Path:
        """Draw it to a PNG, SVG or PDF (atomically) and return the path."""
        from sinews.render import plot_fitness

        return plot_fitness(self.generations, self.series, path, self.title, marks=self.marks)


def fitness_plot(store: RunStore, run_id: int) -> FitnessPlot:
    """A run's best and mean fitness per generation and the terms of each generation's best
    (and, with style phased in, the best rated at full weight), as ``sinews plot`` draws them."""
    info = store.run(run_id)
    config = EvolutionConfig.from_dict(info.config)
    if config.by_hand:
        raise SinewsError(f"run {run_id} is bred by hand: it has picks, not fitness, to plot")
    stats = generation_stats(store.scores(run_id))
    if not len(stats.generations):
        raise SinewsError(f"run {run_id} has no scored generations yet")
    spec = config.fitness
    weighed = {k: v for k, v in stats.best_terms.items() if spec.weights.get(k, 1.0) != 0}
    terms = weighed if len(weighed) > 1 else {}  # one term: = best; weight 0: not rated
    series = {"best": stats.best, "mean": stats.mean, **terms}
    marks: dict[str, float] = {}
    if spec.final > 0 and len(weighed) > 1:  # early bests are rated without style
        series["best at full weight"] = full_weight_bests(store.scores(run_id), spec)
        together = spec.constraints and spec.constraints_start == spec.phase_in.start
        start = "style and constraints start" if together else "style starts"
        marks = {start: spec.phase_in.start, "style full": spec.phase_in.full}
        if spec.constraints and not together and spec.constraints_start <= stats.generations[-1]:
            marks["constraints start"] = spec.constraints_start
    marks.update({f"restart at {g}": g for g in store.restarts(run_id)})
    song = info.config.get("song", "")
    title = f"run {run_id}: {info.kind}{f' to {song}' if song else ''}"
    title += " (terms of each best)" if terms else ""
    title += f", seed {info.seed}\n{fitness_label(info)}"
    return FitnessPlot(np.asarray(stats.generations), series, title, marks)


def fitness_label(info: RunInfo) -> str:
    """What a run's fitness measures, for plots: its kind's label, or a figure dance's."""
    kind = kind_of(info)
    dance = info.song_hash is not None and kind.name != "dancers"
    return DANCE_LABEL if dance else kind.fitness_label
