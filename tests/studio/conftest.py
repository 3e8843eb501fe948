"""Studio fixtures: a real ``sinews studio`` server in a subprocess and headless Chromium.

The server runs with ``--port 0`` on 127.0.0.1, a temporary database, and
temporary XDG data and cache folders (the demo song and song analyses go
there, not into the user's home). Chromium is Debian's (``/usr/bin/chromium``),
driven by Playwright's sync API; Playwright's own browser download is never used.
Screenshots go to ``$SINEWS_STUDIO_SHOTS`` if set, else a temporary folder.
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from figure_page_helpers import GP, SPRINGNET, copy_of, sinews
from studio_helpers import CHROMIUM, CHROMIUM_ARGS, StudioServer

LIVENESS_MS = 60_000
"""How long a page action or `expect` waits before failing (Playwright's defaults: 30 s, 5 s)."""


@pytest.fixture(scope="session")
def studio_env(tmp_path_factory: pytest.TempPathFactory) -> dict[str, str]:
    """Environment for studio subprocesses: private XDG data and cache folders."""
    root = tmp_path_factory.mktemp("studio-xdg")
    return {
        **os.environ,
        "XDG_DATA_HOME": str(root / "data"),
        "XDG_CACHE_HOME": str(root / "cache"),
    }


@pytest.fixture(scope="session")
def lamp_runs(tmp_path_factory: pytest.TempPathFactory, studio_env: dict[str, str]) -> Path:
    """A database with a spring-net run (1) and a GP run (2) of the lamp, made by the CLI once;
    copy it (`copy_of`) before changing it."""
    db = tmp_path_factory.mktemp("lamp-runs") / "studio.db"
    sinews(db, studio_env, "evolve", *SPRINGNET)
    sinews(db, studio_env, "evolve", *GP)
    return db


@pytest.fixture(scope="module")
def lamp_db(tmp_path_factory: pytest.TempPathFactory, lamp_runs: Path) -> Path:
    """This module's copy of `lamp_runs`."""
    return copy_of(lamp_runs, tmp_path_factory.mktemp("lamps"))


@pytest.fixture(scope="module")
def lamp_server(lamp_db: Path, studio_env: dict[str, str]) -> Iterator[StudioServer]:
    """A studio on this module's `lamp_db`."""
    studio = StudioServer(lamp_db, studio_env)
    yield studio
    studio.stop()


@pytest.fixture(scope="session")
def studio_home(studio_env: dict[str, str]) -> Iterator[None]:
    """Point this process's XDG folders at the private ones (for in-process studio tests)."""
    with pytest.MonkeyPatch.context() as patch:
        for name in ("XDG_DATA_HOME", "XDG_CACHE_HOME"):
            patch.setenv(name, studio_env[name])
        yield


@pytest.fixture(scope="session")
def server(
    tmp_path_factory: pytest.TempPathFactory, studio_env: dict[str, str]
) -> Iterator[StudioServer]:
    """One studio server for the browser tests that do not restart it."""
    db = tmp_path_factory.mktemp("studio-db") / "studio.db"
    studio = StudioServer(db, studio_env)
    yield studio
    studio.stop()


@pytest.fixture(scope="session")
def playwright() -> Iterator[Any]:
    """Playwright's sync API, started once (it cannot be started twice at a time), or a skip
    when Chromium is not installed."""
    if not CHROMIUM.exists():
        pytest.skip(f"browser tests need Chromium at {CHROMIUM} (apt-get install chromium)")
    from playwright.sync_api import expect, sync_playwright

    # Liveness bounds, not timing claims: the suite runs one worker per core, so a page may
    # wait while the other worker compiles or simulates (pages set the same for actions).
    expect.set_options(timeout=LIVENESS_MS)
    with sync_playwright() as started:
        yield started


@pytest.fixture(scope="session")
def browser(playwright: Any) -> Iterator[Any]:
    """Headless Debian Chromium."""
    chromium = playwright.chromium.launch(executable_path=str(CHROMIUM), args=CHROMIUM_ARGS)
    yield chromium
    chromium.close()


@pytest.fixture
def page(browser: Any) -> Iterator[Any]:
    """A fresh page (its own context) that fails the test on any JavaScript error.

    Refused requests (4xx, which the page reports as one-line messages) are expected.
    """
    context = browser.new_context(viewport={"width": 1600, "height": 1000}, accept_downloads=True)
    context.set_default_timeout(LIVENESS_MS)
    page = context.new_page()
    errors: list[str] = []
    page.on("pageerror", lambda error: errors.append(str(error)))
    page.on(
        "console",
        lambda m: (
            errors.append(m.text) if m.type == "error" and "status of 4" not in m.text else None
        ),
    )
    yield page
    context.close()
    assert not errors, f"JavaScript errors: {errors}"


@pytest.fixture(scope="session")
def shots(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """Where screenshots go (look at them)."""
    folder = Path(os.environ.get("SINEWS_STUDIO_SHOTS") or tmp_path_factory.mktemp("shots"))
    folder.mkdir(parents=True, exist_ok=True)
    return folder
