"""Dancers end to end: genomes develop into bodies, one batched rollout, trajectories out."""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from sinews.dancers import DANCER_ENGINE, DancerGenome, develop
from sinews.dancers.groove import groove_signals
from sinews.dancers.responders import beat_drive
from sinews.errors import SinewsError
from sinews.limits import MAX_SECONDS
from sinews.music import MusicFeatures
from sinews.music.spectrum import DEFAULT_BANDS
from sinews.springmass import BodyBatch, Recording, SimState, simulate
from sinews.trajectory import Trajectory

__all__ = ["MAX_SECONDS", "DanceSetup", "dance", "new_genome", "prepare_dance", "random_genomes"]


def new_genome(seed: int) -> DancerGenome:
    """A random dancer genome from ``seed``."""
    return DancerGenome.random(np.random.default_rng(seed))


def random_genomes(seed: int, count: int) -> list[DancerGenome]:
    """``count`` random genomes from one ``seed`` (the i-th does not depend on count)."""
    if count < 1:
        raise SinewsError("count must be at least 1")
    children = np.random.SeedSequence(seed).spawn(count)
    return [DancerGenome.random(np.random.default_rng(child)) for child in children]


@dataclass(frozen=True, eq=False)
class DanceSetup:
    """What a dance is simulated from (`dance` and the studio's live dancer share it).

    Attributes:
        batch: the developed bodies with their wiggle seeds.
        n_steps: engine steps of the whole dance.
        drive: the music's band moves on the beat grid (frames, bands), or None
            (`sinews.dancers.responders.beat_drive`).
        phase: the music's two-beat phase (frames,), or None.
        pose: the groove's signals (frames, 2), or None
            (`sinews.dancers.groove.groove_signals`).
    """

    batch: BodyBatch
    n_steps: int
    drive: npt.NDArray[np.float32] | None
    phase: npt.NDArray[np.float32] | None
    pose: npt.NDArray[np.float32] | None


def prepare_dance(
    genomes: Sequence[DancerGenome],
    seconds: float | None = None,
    *,
    music: MusicFeatures | None = None,
    responders: bool = True,
    seeds: Sequence[int] | None = None,
) -> DanceSetup:
    """Develop the dancers and line the music up with the engine (see `dance` for the args)."""
    if seconds is None:
        if music is None:
            raise SinewsError("give the dance a length in seconds or a song")
        seconds = music.duration
    if not 0 < seconds <= MAX_SECONDS:
        raise SinewsError(f"seconds must be in (0, {MAX_SECONDS:g}], got {seconds:g}")
    n_bands = DEFAULT_BANDS if music is None else music.n_bands
    bodies = [develop(g, n_bands=n_bands) for g in genomes]
    if not responders:
        bodies = [b.without_actuators() for b in bodies]
    if music is not None and music.fps * DANCER_ENGINE.dt != 1.0:
        raise SinewsError(f"the song was analysed at {music.fps:g} fps; dancers step at 60")
    n_steps = max(1, round(seconds / DANCER_ENGINE.dt))
    drive, phase = (None, None) if music is None else beat_drive(music)
    pose = groove_signals(music) if music is not None and responders else None
    return DanceSetup(
        batch=BodyBatch.from_bodies(bodies, seeds=seeds),
        n_steps=n_steps,
        drive=drive,
        phase=phase,
        pose=pose,
    )


def dance(
    genomes: Sequence[DancerGenome],
    seconds: float | None = None,
    *,
    music: MusicFeatures | None = None,
    responders: bool = True,
    seeds: Sequence[int] | None = None,
    record_forces: bool = False,
) -> list[Trajectory]:
    """Simulate the dancers together in one batch and return one trajectory each.

    Args:
        genomes: the dancers.
        seconds: length of the dance (default: the whole song).
        music: the analysed song their responders listen to; without it they
            move only by wiggle and home.
        responders: False switches every responder and the groove off (to hear what
            the music adds).
        seeds: one wiggle-noise seed per dancer (default 0 for all); a dancer's
            motion depends only on its genome, its seed and the music.
        record_forces: keep per-node forces for the debug overlay.

    Returns:
        Trajectories at the engine's 60 frames per second, frame 0 the rest
        pose; with music they carry its beats and each responder's triggers.
    """
    setup = prepare_dance(genomes, seconds, music=music, responders=responders, seeds=seeds)
    batch = setup.batch
    state, recording = simulate(
        batch,
        batch.initial_state(),
        setup.n_steps,
        DANCER_ENGINE,
        drive=setup.drive,
        phase=setup.phase,
        pose=setup.pose,
        record_forces=record_forces,
    )
    assert recording is not None
    return [_trajectory(recording, batch, state, p, music) for p in range(batch.size)]


def _trajectory(
    recording: Recording, batch: BodyBatch, state: SimState, index: int, music: MusicFeatures | None
) -> Trajectory:
    traj = recording.trajectory(batch, state, index)
    if music is None:
        return traj
    body = batch.bodies[index]
    frames = np.minimum(np.arange(traj.n_frames), len(music.triggers) - 1)
    fired = np.zeros((traj.n_frames, body.n_actuators), dtype=bool)
    for r, (lo, hi) in enumerate(body.actuator_channels):
        fired[:, r] = music.triggers[frames, lo : hi + 1].any(axis=1)
    fired[np.arange(traj.n_frames) >= len(music.triggers)] = False
    return dataclasses.replace(
        traj, beats=music.beats, triggers=fired, trigger_nodes=body.actuator_node
    )
