"""What the page plays: generations and single dancers, danced and packed as binary arrays.

A generation is replayed by the dancer run kind (`RunKind.replay`: one batched
rollout with each dancer's stored wiggle seed), so it moves exactly as it would
anywhere else, and sent as int16 millimetres. The dancer on the stage is
danced alone with its forces recorded (the debug overlay), possibly with
some main body genes changed by the sliders, and sent as float32. Recent
results are kept, keyed by everything they depend on.
"""

from __future__ import annotations

from collections import OrderedDict
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any, TypeVar

import numpy as np

from sinews.dancers import DancerGenome, develop
from sinews.evolve import Strategy, restore_strategy
from sinews.experiments.dancers.run import KIND
from sinews.experiments.dancers.simulate import dance
from sinews.music import MusicFeatures
from sinews.store import Individual
from sinews.studio.pack import MILLIMETRES, encode_pack, millimetres
from sinews.studio.runs import StudioError, StudioRuns
from sinews.trajectory import Trajectory

__all__ = ["SLIDER_GENES", "Motion", "Recent", "StageDancer"]

SLIDER_GENES = ("stiffness", "bulkiness", "lankiness", "torso_triangularity")
"""The main body genes the stage's sliders change."""

T = TypeVar("T")

GENERATIONS_KEPT = 96 * 2**20
"""Bytes of generation packs kept for the page (three six-minute generations of 20)."""


@dataclass(frozen=True, eq=False)
class StageDancer:
    """One stored dancer, possibly with changed body genes, and the song it dances to.

    Attributes:
        individual: the stored dancer.
        genome: its genome with the changes applied.
        music: the run's analysed song.
        song: the song's file.
        seconds: the run's dance length.
    """

    individual: Individual
    genome: DancerGenome
    music: MusicFeatures
    song: Path
    seconds: float

    def dance(self, seconds: float | None = None, *, record_forces: bool = False) -> Trajectory:
        """Its dance (default: the run's whole length)."""
        (traj,) = dance(
            [self.genome],
            seconds or self.seconds,
            music=self.music,
            seeds=[int(self.individual.seed or 0)],
            record_forces=record_forces,
        )
        return traj


class Recent:
    """The last few results by key (a tiny LRU cache).

    Args:
        size: most results kept.
        budget: most bytes kept, counting results that are `bytes` (the newest
            is always kept).
    """

    def __init__(self, size: int, budget: int | None = None) -> None:
        self.size = size
        self.budget = budget
        self._items: OrderedDict[Any, Any] = OrderedDict()

    def _bytes(self) -> int:
        return sum(len(v) for v in self._items.values() if isinstance(v, bytes))

    def get(self, key: Any, make: Callable[[], T]) -> T:
        if key in self._items:
            self._items.move_to_end(key)
            return self._items[key]
        value = make()
        self._items[key] = value
        while len(self._items) > self.size or (
            self.budget is not None and len(self._items) > 1 and self._bytes() > self.budget
        ):
            self._items.popitem(last=False)
        return value


class Motion:
    """Dances generations and stage dancers for the page.

    Args:
        runs: the studio's runs.
    """

    def __init__(self, runs: StudioRuns) -> None:
        self.runs = runs
        self._generations = Recent(6, GENERATIONS_KEPT)
        self._stage = Recent(4)

    def generation(self, run_id: int, generation: int) -> bytes:
        """A generation as a pack: header with the dancers, positions (P, T, N, 2) int16 mm."""
        run = self.runs.get(run_id)
        key = (run_id, generation, run.bpm, run.beat_shift)
        return self._generations.get(key, lambda: self._generation(run_id, generation))

    def dance_generation(
        self, run_id: int, generation: int
    ) -> tuple[list[Individual], list[Trajectory]]:
        """A stored generation and its dances (one batched rollout)."""
        self.runs.get(run_id)  # refuses a run the studio cannot open
        people = self.runs.store.individuals(run_id, generation)
        if not people:
            raise StudioError(f"run {run_id} has no generation {generation}")
        return people, [r.trajectory for r in KIND.replay(self.runs.store, people)]

    def _generation(self, run_id: int, generation: int) -> bytes:
        people, trajs = self.dance_generation(run_id, generation)
        # int16 one dancer at a time: a float copy of a six-minute generation is 110 MB
        positions = np.stack([millimetres(t.positions) for t in trajs])
        strategy = restore_strategy(self.runs.store.checkpoint(run_id, generation))
        assert isinstance(strategy, Strategy)  # dancers breed with float strategies
        header = {
            "run": run_id,
            "generation": generation,
            "fps": trajs[0].fps,
            "frames": trajs[0].n_frames,
            "scale": MILLIMETRES,
            "mutation": strategy.variation.mutation_sigma,
            "names": list(trajs[0].node_names),
            "dancers": [_dancer_header(p, t) for p, t in zip(people, trajs, strict=True)],
        }
        return encode_pack(header, {"positions": positions})

    def stage_dancer(self, individual_id: int, genes: Mapping[str, float]) -> StageDancer:
        """A stored dancer with some of `SLIDER_GENES` changed."""
        unknown = sorted(set(genes) - set(SLIDER_GENES))
        if unknown:
            raise StudioError(f"no slider for the gene {unknown[0]!r}")
        individual = self.runs.store.individual(individual_id)
        run = self.runs.get(individual.run_id)
        music, song = self.runs.music(run.id)
        genome = DancerGenome(individual.genome).replace(**genes)
        return StageDancer(individual, genome, music, song, run.seconds)

    def stage(self, individual_id: int, genes: Mapping[str, float]) -> bytes:
        """The stage dancer as a pack: positions and forces (T, N, 2) float32, triggers (T, R)."""
        dancer = self.stage_dancer(individual_id, genes)
        key = (individual_id, tuple(sorted(genes.items())), dancer.music.beats.tobytes())
        return self._stage.get(key, lambda: _stage_pack(dancer))

    def lineage(self, individual_id: int) -> list[dict[str, Any]]:
        """The dancer and its ancestors, newest first, each with its rest pose."""
        self.runs.get(self.runs.store.individual(individual_id).run_id)
        found = []
        for person in self.runs.store.lineage(individual_id):
            body = develop(DancerGenome(person.genome))
            found.append(
                {
                    **_person(person),
                    "pose": np.round(body.rest, 3).tolist(),
                    "radii": np.round(body.radius, 3).tolist(),
                    "colors": _colors(body.colors),
                    "edges": body.edges.tolist(),
                }
            )
        return found


def _person(person: Individual) -> dict[str, Any]:
    return {
        "id": person.id,
        "run": person.run_id,
        "generation": person.generation,
        "index": person.index,
        "parents": list(person.parents),
        "picked": person.picked,
    }


def _colors(colors: Any) -> list[list[int]]:
    return [] if colors is None else np.asarray(colors, dtype=int).tolist()


def _dancer_header(person: Individual, traj: Trajectory) -> dict[str, Any]:
    return {
        **_person(person),
        "failed": traj.failed,
        "radii": np.round(np.asarray(traj.radii), 3).tolist(),
        "colors": _colors(traj.colors),
        "edges": traj.edges.tolist(),
    }


def _stage_pack(dancer: StageDancer) -> bytes:
    traj = dancer.dance(record_forces=True)
    assert traj.forces is not None
    triggers = np.zeros((traj.n_frames, 0), bool) if traj.triggers is None else traj.triggers
    nodes = np.zeros(0, int) if traj.trigger_nodes is None else traj.trigger_nodes
    header = {
        **_person(dancer.individual),
        "fps": traj.fps,
        "frames": traj.n_frames,
        "failed": traj.failed,
        "names": list(traj.node_names),
        "edges": traj.edges.tolist(),
        "radii": np.round(np.asarray(traj.radii), 3).tolist(),
        "colors": _colors(traj.colors),
        "triggerNodes": np.asarray(nodes).tolist(),
        "genes": dancer.genome.body,
        "tempo": dancer.music.tempo_bpm,
    }
    arrays = {
        "positions": np.nan_to_num(traj.positions).astype(np.float32),
        "forces": np.nan_to_num(traj.forces).astype(np.float32),
        "triggers": np.asarray(triggers, dtype=bool),
    }
    return encode_pack(header, arrays)
