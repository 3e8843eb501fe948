"""Song commands: ``sinews songs demo``, ``sinews songs analyse`` and ``sinews score``."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import numpy as np
import typer

from sinews.experiments.dancers.settings import song_path
from sinews.music import (
    DEFAULT_DEMO,
    DEMO_NAMES,
    analyse_file,
    beat_align_score,
    beat_lift,
    kinematic_beats,
    smoothness,
    write_demo,
)
from sinews.music.analysis import MAX_BPM, MIN_BPM
from sinews.trajectory import Trajectory, TrajectoryError

__all__ = ["register"]

songs_app = typer.Typer(help="Demo songs and song analysis.", no_args_is_help=True)

Bpm = Annotated[
    float | None,
    typer.Option(min=MIN_BPM, max=MAX_BPM, help="The tempo, if known (skips tempo detection)."),
]


@songs_app.command("demo")
def demo(
    output: Annotated[
        Path, typer.Option("-o", "--output", help="File to write (.wav, .flac, .ogg, .mp3).")
    ] = Path("demo.wav"),
    name: Annotated[
        str, typer.Option(help=f"Which demo song: {', '.join(DEMO_NAMES)}.")
    ] = DEFAULT_DEMO,
) -> None:
    """Synthesise a demo song (deterministic, about 50 s) and write it to a file."""
    path = write_demo(name, output)
    typer.echo(f"wrote {path}")


@songs_app.command("analyse")
def analyse(
    song: Annotated[Path, typer.Argument(help="Song file (WAV, FLAC, OGG, MP3, M4A).")],
    bpm: Bpm = None,
) -> None:
    """Analyse a song (cached) and print its length, tempo and beats."""
    features = analyse_file(song, bpm=bpm)
    typer.echo(
        f"{song}: {features.duration:.1f} s, {features.tempo_bpm:.1f} BPM, "
        f"{len(features.beats)} beats, {features.n_bands} bands, "
        f"{int(features.triggers.sum())} band triggers"
    )


def score(
    trajectory: Annotated[Path, typer.Argument(help="Trajectory file (.npz).")],
    song: Annotated[
        str | None,
        typer.Option(
            help="Song to take the beats from, or demo:groove / demo:sway "
            "(default: the beats saved in the file)."
        ),
    ] = None,
    bpm: Bpm = None,
) -> None:
    """Print how well a motion follows the beats: beat lift, smoothness and beat-align.

    Beat lift is beat-align with the beats minus its mean over 16 phase shifts of
    them (0: ignores the beat, however often it pauses); smoothness is the share of
    the motion's energy below 4 Hz (docs/dancing.md).
    """
    traj = Trajectory.load(trajectory)
    beats = traj.beats if song is None else analyse_file(song_path(song), bpm=bpm).beats
    if beats is None:
        raise TrajectoryError(f"{trajectory}: no beats saved in the file; pass --song SONG")
    value = beat_align_score(traj.positions, traj.fps, beats)
    lift = beat_lift(traj.positions, traj.fps, beats)
    smooth = smoothness(traj.positions, traj.fps)
    duration = (len(traj.positions) - 1) / traj.fps
    heard = np.count_nonzero((np.asarray(beats) >= 0) & (np.asarray(beats) <= duration))
    pauses = len(kinematic_beats(traj.positions, traj.fps))
    typer.echo(
        f"beat lift {lift:.3f}, smoothness {smooth:.3f}, beat-align score {value:.3f} "
        f"({heard} music beats and {pauses} kinematic beats in the {duration:.1f} s motion)"
    )


def register(app: typer.Typer) -> None:
    """Add the ``songs`` commands and ``score`` to ``app``."""
    app.add_typer(songs_app, name="songs")
    app.command("score")(score)
