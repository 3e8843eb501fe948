"""Dancer commands: ``sinews dancer new``, ``sinews dance``, ``sinews sheet``."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from sinews.cli.progress import frame_progress
from sinews.cli.songs import Bpm
from sinews.dancers import DancerGenome
from sinews.experiments.dancers import simulate as experiment
from sinews.experiments.dancers.settings import song_path
from sinews.limits import MAX_PICTURE_PIXELS, MIN_PICTURE_PIXELS
from sinews.music.analysis import analyse_file
from sinews.render import contact_sheet, render

__all__ = ["register"]

dancer_app = typer.Typer(help="Make and inspect dancer genomes.", no_args_is_help=True)

Output = Annotated[Path, typer.Option("-o", "--output", help="File to write.")]
Seed = Annotated[int, typer.Option(help="Random seed.")]


@dancer_app.command("new")
def new(output: Output, seed: Seed = 0) -> None:
    """Write a random dancer genome to a JSON file."""
    path = experiment.new_genome(seed).save(output)
    typer.echo(f"wrote {path}")


def dance(
    genome: Annotated[Path, typer.Argument(help="Dancer genome JSON.")],
    output: Output,
    song: Annotated[
        str | None,
        typer.Option(help="Music (WAV, FLAC, OGG, MP3, M4A), or demo:groove / demo:sway."),
    ] = None,
    seconds: Annotated[
        float | None, typer.Option(help="Length of the dance (default: the song, or 8 s).")
    ] = None,
    bpm: Bpm = None,
    seed: Seed = 0,
    trajectory: Annotated[
        Path | None, typer.Option(help="Also save the motion as a .npz trajectory.")
    ] = None,
    debug_overlay: Annotated[bool, typer.Option(help="Draw node labels and force arrows.")] = False,
    size: Annotated[
        int,
        typer.Option(
            min=MIN_PICTURE_PIXELS, max=MAX_PICTURE_PIXELS, help="Picture size in pixels."
        ),
    ] = 480,
) -> None:
    """Let a dancer dance and draw it (.png, .svg, .gif, or .mp4 with the song as sound)."""
    dancer = DancerGenome.load(genome)
    song_file = None if song is None else song_path(song)
    music = None if song_file is None else analyse_file(song_file, bpm=bpm)
    if seconds is None and music is None:
        seconds = 8.0
    (traj,) = experiment.dance(
        [dancer], seconds, music=music, seeds=[seed], record_forces=debug_overlay
    )
    if trajectory is not None:
        traj.save(trajectory)
        typer.echo(f"wrote {trajectory}")
    sound = (
        {"audio": song_file} if song_file is not None and output.suffix.lower() == ".mp4" else {}
    )
    with frame_progress("dance"):
        path = render(traj, output, overlay=debug_overlay, size=size, **sound)
    typer.echo(f"wrote {path}")


def sheet(
    output: Output,
    seed: Seed = 0,
    count: Annotated[int, typer.Option(help="How many dancers.", min=1, max=400)] = 16,
    seconds: Annotated[float, typer.Option(help="Moment of the dance to show.")] = 2.0,
) -> None:
    """Draw a contact sheet of random dancers (many morphologies in one generation)."""
    genomes = experiment.random_genomes(seed, count)
    trajs = experiment.dance(genomes, seconds, seeds=list(range(count)))
    path = contact_sheet(trajs, output, labels=[f"#{i}" for i in range(count)])
    typer.echo(f"wrote {path}")


def register(app: typer.Typer) -> None:
    """Add the dancer commands to ``app``."""
    app.add_typer(dancer_app, name="dancer")
    app.command("dance")(dance)
    app.command("sheet")(sheet)
