"""What the figure page plays: a generation of figures replayed and packed as geom poses.

A generation is replayed by its run kind (`RunKind.replay`, one batch, exactly
as it was scored), every frame's geoms placed by forward kinematics
(`FigureGeometry.poses`) and sent as int16 millimetres (`sinews.studio.pack`):
a cell then only draws capsules, boxes and spheres where the pack says. The
header names the drawer: ``"planar"`` (geoms in the x-z plane) or, for a 3D
figure, ``"solid"`` (every shape's 3D pose, `sinews.studio.shapes_pack`, drawn
with three.js). A pack holds, beside the poses, what a cell is labelled
with (fitness and its terms), the task's scene (`sinews.render.figure_scene`)
and each controller: a spring net's masses, springs and motion (the net
panel) or a GP program's S-expression.
"""

from __future__ import annotations

from dataclasses import asdict
from typing import Any

import numpy as np

from sinews.experiments.kinds import Replay
from sinews.figures.geoms import shapes_of
from sinews.render.figure_geometry import FigureGeometry
from sinews.render.figure_panel import NetPanel
from sinews.render.style import default_colors
from sinews.store import Individual
from sinews.studio.figure_runs import (
    MAX_SHOWN,
    POSE_HZ,
    FigureRun,
    FigureRunError,
    FigureRuns,
)
from sinews.studio.motion import Recent
from sinews.studio.pack import MILLIMETRES, encode_pack, millimetres
from sinews.studio.shapes_pack import encode_shapes

__all__ = ["POSE_HZ", "FigureMotion"]

PACKS_KEPT = 64 * 2**20
"""Bytes of generation packs kept."""


class FigureMotion:
    """Replays and packs generations of figure runs.

    Args:
        runs: the store's figure runs.
    """

    def __init__(self, runs: FigureRuns) -> None:
        self.runs = runs
        self._packs = Recent(8, PACKS_KEPT)

    def generation(self, run_id: int, generation: int) -> bytes:
        """A generation as a pack: header, then (P, T, K, 2) int16 ``centers``, ``ax``, ``az``
        (geoms' centres, mm, and unit axes, thousandths), (P, T, S, 2) ``sites``, (P, T)
        ``root_x`` mm, and for spring nets (P, T, n) float32 ``net`` positions."""
        run = self.runs.get(run_id)
        people = self.runs.store.individuals(run_id, generation)
        if not people:
            raise FigureRunError(f"run {run_id} has no generation {generation}")
        key = (run_id, generation, tuple(p.picked for p in people))
        return self._packs.get(key, lambda: self._pack(run, people, generation))

    def timeline(self, run_id: int) -> bytes:
        """The learning timeline (`timeline_bests`) as one pack (``generation`` -1)."""
        run = self.runs.get(run_id)
        bests = self.timeline_bests(run_id)
        last = bests[-1].generation
        return self._packs.get((run_id, "timeline", last), lambda: self._pack(run, bests, -1))

    def timeline_bests(self, run_id: int) -> list[Individual]:
        """The best of each generation (at most `MAX_SHOWN`, evenly spaced, the first and the
        last among them) by stored fitness, oldest first: the run learning."""
        store = self.runs.store
        last = store.last_generation(run_id)
        if last < 0:
            raise FigureRunError(f"run {run_id} has no generation yet")
        chosen = np.unique(np.linspace(0, last, min(last + 1, MAX_SHOWN)).round().astype(int))
        table = store.scores(run_id)
        bests = []
        for generation in chosen.tolist():
            rows = np.flatnonzero(table.generation == generation)
            if len(rows):
                best = rows[int(np.argmax(table.fitness[rows]))]
                bests.append(store.individuals(run_id, generation)[int(table.index[best])])
        if not bests:
            raise FigureRunError(f"run {run_id} has no scored generation")
        return bests

    def timeline_replays(self, run_id: int) -> list[Replay]:
        """The learning timeline replayed for a video (`sinews.render.replays.draw_replays`)."""
        run = self.runs.get(run_id)
        return run.kind.replay(self.runs.store, self.timeline_bests(run_id))

    def _pack(self, run: FigureRun, people: list[Individual], generation: int) -> bytes:
        replays = run.kind.replay(self.runs.store, people, record_hz=POSE_HZ,
                                  log=self.runs.motion_log(run.id))  # fmt: skip
        programs = [run.kind.genome_text(p) for p in people]
        return _pack(run.id, generation, replays, programs)


def _pack(run_id: int, generation: int, replays: list[Replay], programs: list[str | None]) -> bytes:
    figure = replays[0].figure
    if figure.root == "free":
        model = figure.model()
        return encode_shapes(
            [shapes_of(model, np.asarray(r.trajectory.qpos)) for r in replays],
            replays[0].trajectory.fps,
            run=run_id,
            generation=generation,
            drawer="solid",
            frames=replays[0].trajectory.n_frames,
            figure=figure.name,
            scene=None,
            individuals=[_individual(r, p) for r, p in zip(replays, programs, strict=True)],
        )
    geometry = FigureGeometry.of(figure)
    qpos = [np.asarray(r.trajectory.qpos) for r in replays]  # figures' trajectories carry it
    poses = [geometry.poses(q) for q in qpos]
    first = replays[0].trajectory
    scene = replays[0].scene
    colors = default_colors(len(figure.body_names))
    header = {
        "run": run_id,
        "generation": generation,
        "drawer": "planar",
        "fps": first.fps,
        "frames": first.n_frames,
        "scale": MILLIMETRES,
        "figure": figure.name,
        "geoms": {
            "kinds": geometry.kinds.tolist(),
            "half": np.round(geometry.half, 4).tolist(),
            "colors": colors[geometry.body].tolist(),
        },
        "joints": list(figure.joints),
        "jointColors": colors[geometry.joint_bodies].tolist(),
        "sites": list(figure.sites),
        "scene": None if scene is None else _scene(asdict(scene)),
        "individuals": [_individual(r, p) for r, p in zip(replays, programs, strict=True)],
    }
    arrays = {
        "centers": np.stack([millimetres(p.centers) for p in poses]),
        "ax": np.stack([millimetres(p.ax) for p in poses]),
        "az": np.stack([millimetres(p.az) for p in poses]),
        "sites": np.stack([millimetres(p.sites) for p in poses]),
        "root_x": np.stack([millimetres(q[:, 0]) for q in qpos]),
    }
    if isinstance(replays[0].panel, NetPanel):
        arrays["net"] = np.stack([np.asarray(r.panel.positions, np.float32) for r in replays])
    return encode_pack(header, arrays)


def _scene(fields: dict[str, Any]) -> dict[str, Any]:
    return {
        "cross": fields["cross"],
        "posts": [list(p) for p in fields["posts"]],
        "target": None if fields["target"] is None else list(fields["target"]),
        "targetSite": fields["target_site"],
        "trackedSite": fields["tracked_site"],
    }


def _individual(replay: Replay, program: str | None) -> dict[str, Any]:
    person: Individual = replay.individual
    found: dict[str, Any] = {
        "id": person.id,
        "index": person.index,
        "generation": person.generation,
        "fitness": _finite(person.fitness),
        "terms": {k: _finite(v) for k, v in (person.terms or {}).items()},
        "picked": person.picked,
        "failed": person.failed or replay.trajectory.failed,
        "parents": list(person.parents),
        "distance": replay.distance,
    }
    panel = replay.panel
    if isinstance(panel, NetPanel):
        found["net"] = {
            "masses": np.round(panel.masses, 4).tolist(),
            "springs": np.round(panel.springs, 3).tolist(),
            "outputs": np.asarray(panel.outputs).tolist(),
            "labels": list(panel.labels),
        }
    if program is not None:
        found["program"] = program
    return found


def _finite(value: float | None) -> float | None:
    return None if value is None or not np.isfinite(value) else float(value)
