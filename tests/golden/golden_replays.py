"""The one place the golden test reaches into the library: replay a run's best to positions."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import numpy.typing as npt

from sinews.experiments.kinds import kind_of
from sinews.store import RunStore


def replay_positions(store: RunStore, run_id: int) -> npt.NDArray[np.floating]:
    """(T, ...) the replayed motion of individual 1 of the run's last generation: dancer
    node positions or figure qpos (a fixed individual, whatever "best" means)."""
    individual = store.individuals(run_id, store.last_generation(run_id))[1]
    (replay,) = kind_of(store.run(run_id)).replay(store, [individual])
    qpos = replay.trajectory.qpos
    return replay.trajectory.positions if qpos is None else qpos


def studio_session(store: RunStore, songs: Path) -> list[int]:
    """A scripted studio session; returns the runs it made (the first run, then its branch)."""
    from sinews.studio.runs import StudioRuns
    from sinews.studio.songs import SongLibrary

    runs = StudioRuns(store, SongLibrary(songs), population=12)
    first = runs.create(runs.songs.demo(), seed=4)
    runs.breed(first, 0, [3, 5], mutation=0.1)
    runs.breed(first, 1, [1], mutation=0.25)
    branch, _ = runs.breed(first, 1, [0, 7], mutation=0.05)
    return [first, branch]
