"""Dancer commands: ``sinews dancer new``, ``sinews dance``, ``sinews sheet``."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from sinews.dancers import DancerGenome
from sinews.experiments import dancers as experiment
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
    seconds: Annotated[float, typer.Option(help="Length of the dance.")] = 8.0,
    seed: Seed = 0,
    trajectory: Annotated[
        Path | None, typer.Option(help="Also save the motion as a .npz trajectory.")
    ] = None,
    debug_overlay: Annotated[bool, typer.Option(help="Draw node labels and force arrows.")] = False,
    size: Annotated[int, typer.Option(help="Picture size in pixels.")] = 480,
) -> None:
    """Let a dancer dance and draw it (.png, .svg, .gif or .mp4)."""
    dancer = DancerGenome.load(genome)
    (traj,) = experiment.dance([dancer], seconds, seeds=[seed], record_forces=debug_overlay)
    if trajectory is not None:
        traj.save(trajectory)
        typer.echo(f"wrote {trajectory}")
    path = render(traj, output, overlay=debug_overlay, size=size)
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
