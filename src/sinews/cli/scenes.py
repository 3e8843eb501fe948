"""Scene command: ``sinews scene NAME`` plays a prototype headless and draws it."""

from __future__ import annotations

import time
from pathlib import Path
from typing import Annotated

import numpy as np
import typer

from sinews.cli.progress import frame_progress
from sinews.limits import MAX_PICTURE_PIXELS, MIN_PICTURE_PIXELS
from sinews.scenes.catalog import SCENE_NAMES, make_scene, player
from sinews.scenes.video import save_scene

__all__ = ["register"]


def scene(
    name: Annotated[str, typer.Argument(help=f"Which scene: {', '.join(SCENE_NAMES)}.")],
    output: Annotated[
        Path, typer.Option("-o", "--output", help="File to write (.mp4, or .png/.gif/.svg).")
    ],
    seconds: Annotated[float, typer.Option(min=0.0, help="How long to play.")] = 10.0,
    seed: Annotated[int, typer.Option(help="Random seed.")] = 0,
    trajectory: Annotated[
        Path | None, typer.Option(help="Also save the motion as a .npz trajectory.")
    ] = None,
    with_player: Annotated[
        bool,
        typer.Option(
            "--player/--no-player",
            help="Scripted input: fling a kitten every 1.5 s, draw four preset scribbles, "
            "push the main doll right from 7 to 9 s. Without it the scene plays itself.",
        ),
    ] = True,
    debug_overlay: Annotated[bool, typer.Option(help="Draw node labels and force arrows.")] = False,
    height: Annotated[
        int,
        typer.Option(
            min=MIN_PICTURE_PIXELS, max=MAX_PICTURE_PIXELS, help="Picture height in pixels."
        ),
    ] = 360,
) -> None:
    """Play a prototype scene (Falling for You, Kitten Avalanche, Scribbles) and draw it."""
    playing = make_scene(name, np.random.default_rng(seed), record_forces=debug_overlay)
    script = player(playing, np.random.default_rng([seed, 1])) if with_player else None
    started = time.perf_counter()
    run = playing.record(seconds, script)
    per_frame = (time.perf_counter() - started) / max(1, run.trajectory.n_frames - 1)
    if trajectory is not None:
        typer.echo(f"wrote {run.trajectory.save(trajectory)}")
    with frame_progress(name):
        path = save_scene(run, output, height=height, overlay=debug_overlay)
    typer.echo(
        f"wrote {path}: {run.score_name} {run.score[-1]}, "
        f"{1e3 * per_frame:.2f} ms per frame (simulation and scene logic)"
    )


def register(app: typer.Typer) -> None:
    """Add the scene command to ``app``."""
    app.command("scene")(scene)
