"""``sinews studio``: breed dancers in the browser (the interactive evolution studio)."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from sinews.store import default_db_path

__all__ = ["register"]


def studio(
    song: Annotated[
        Path | None,
        typer.Option("--song", help="Song to start on (default: the bundled demo song)."),
    ] = None,
    db: Annotated[
        Path | None, typer.Option("--db", help="Run database (default: the app's data dir).")
    ] = None,
    port: Annotated[
        int, typer.Option(min=0, max=65535, help="Port to serve on (0: any free one).")
    ] = 8765,
    no_browser: Annotated[
        bool, typer.Option("--no-browser", help="Do not open the page in a browser.")
    ] = False,
    resume: Annotated[
        int | None, typer.Option("--resume", help="Continue this run (see sinews runs list).")
    ] = None,
    host: Annotated[
        str, typer.Option(help="Address to listen on; anything but 127.0.0.1 is reachable.")
    ] = "127.0.0.1",
    allow_host: Annotated[
        list[str] | None,
        typer.Option(
            "--allow-host",
            help="With --host: a name or address others use to reach the studio (repeatable).",
        ),
    ] = None,
    population: Annotated[int, typer.Option(help="Dancers per generation, 12 to 20.")] = 16,
) -> None:
    """Breed dancers to music in your browser: pick favourites, breed the next generation."""
    from sinews.studio.server import serve
    from sinews.studio.service import StudioSettings

    settings = StudioSettings(
        db=db or default_db_path(), song=song, resume=resume, population=population
    )
    serve(settings, host=host, port=port, open_browser=not no_browser, allow_hosts=allow_host or [])


def register(app: typer.Typer) -> None:
    """Add ``sinews studio`` to ``app``."""
    app.command("studio")(studio)
