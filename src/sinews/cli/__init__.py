"""The ``sinews`` command line: thin Typer commands, each calling one library function.

Every command module below defines its commands on a `typer.Typer` and is
registered here. Exit statuses: 0 done, 2 a user error (one line on stderr:
a `SinewsError` or a usage error), 130 interrupted by Ctrl-C.
"""

from __future__ import annotations

import signal
import sys

import typer

from sinews.errors import SinewsError

__all__ = ["app", "main"]

INTERRUPTED = 130
USER_ERROR = 2

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


def _usage_errors() -> tuple[type[Exception], ...]:
    """Click's usage-error classes: typer's vendored copy and, if installed, click's own."""
    from typer._click.exceptions import ClickException

    classes: list[type[Exception]] = [ClickException]
    try:
        import click
    except ImportError:
        return tuple(classes)
    return (*classes, click.ClickException)


def _usage_line(exc: Exception) -> str:
    """One line for a usage error: the message and where to look for help."""
    message = " ".join(str(getattr(exc, "format_message", exc.__str__)()).split())
    ctx = getattr(exc, "ctx", None)
    command = ctx.command_path if ctx is not None else "sinews"
    return f"error: {message} (see '{command} --help')"


def main(argv: list[str] | None = None) -> int:
    """Run the CLI; return the exit status (0 ok, 2 user error, 130 interrupted)."""
    signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        _register()
        status = app(args=argv, standalone_mode=False)
    except SinewsError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return USER_ERROR
    except (KeyboardInterrupt, typer.Abort):
        print("interrupted", file=sys.stderr)
        return INTERRUPTED
    except typer.Exit as exc:
        return int(exc.exit_code or 0)
    except _usage_errors() as exc:
        print(_usage_line(exc), file=sys.stderr)
        return USER_ERROR
    return status if isinstance(status, int) else 0
