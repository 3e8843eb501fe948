"""The ``sinews`` command line: thin Typer commands, each calling one library function.

Every command module below defines its commands on a `typer.Typer` and is
registered here. User errors (`SinewsError`) print as one line and exit 2.
"""

from __future__ import annotations

import sys

import typer

from sinews.errors import SinewsError

__all__ = ["app", "main"]

app = typer.Typer(
    name="sinews",
    help="Evolve expressive motion: spring-mass dancers and articulated figures.",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
)


def _register() -> None:
    from sinews.cli.bench import register as register_bench
    from sinews.cli.dancers import register as register_dancers
    from sinews.cli.evolve import register as register_evolve
    from sinews.cli.runs import register as register_runs
    from sinews.cli.scenes import register as register_scenes
    from sinews.cli.songs import register as register_songs
    from sinews.cli.studio import register as register_studio

    register_dancers(app)
    register_songs(app)
    register_bench(app)
    register_evolve(app)
    register_runs(app)
    register_scenes(app)
    register_studio(app)


def main(argv: list[str] | None = None) -> int:
    """Run the CLI; return the exit status (0 ok, 2 user error, 130 interrupted)."""
    _register()
    try:
        app(args=argv, standalone_mode=False)
    except SinewsError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("interrupted", file=sys.stderr)
        return 130
    except typer.Exit as exc:
        return int(exc.exit_code or 0)
    except Exception as exc:  # click usage errors and aborts
        import click

        if isinstance(exc, click.ClickException):
            exc.show()
            return exc.exit_code
        if isinstance(exc, click.exceptions.Abort):
            return 1
        raise
    return 0
