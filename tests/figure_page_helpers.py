"""The figure page's tests' helpers: CLI-made lamp runs, calls to a studio server, stored runs."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import time
import urllib.error
import urllib.request
from pathlib import Path
from typing import Any

import numpy as np

from killed_runs import sinews_command
from sinews.store import RunStore
from studio_helpers import StudioServer

SPRINGNET = ["luxo", "--population", "10", "--generations", "2", "--seconds", "1", "--seed", "3"]
GP = ["luxo", "--controller", "gp", "--task", "hop", "--population", "10", "--generations", "1",
      "--seconds", "1", "--seed", "4"]  # fmt: skip


def sinews(db: Path, env: dict[str, str], *args: str) -> subprocess.CompletedProcess[str]:
    """The installed ``sinews`` on ``db``; fails the test unless it exits 0."""
    done = subprocess.run([*sinews_command(), *args, "--db", str(db)], env=env,
                          capture_output=True, text=True, timeout=600)  # fmt: skip
    assert done.returncode == 0, done.stderr
    return done


def call(server: StudioServer, path: str, body: object = None, **headers: str) -> tuple[int, Any]:
    """GET (or POST ``body`` as JSON) ``path``; (status, JSON or bytes)."""
    data = None if body is None else json.dumps(body).encode()
    if body is not None:
        headers = {"Content-Type": "application/json", **headers}
    request = urllib.request.Request(server.url.rstrip("/") + path, data=data, headers=headers)
    try:
        with urllib.request.urlopen(request, timeout=300) as answer:
            raw, status, kind = answer.read(), answer.status, answer.headers["Content-Type"]
    except urllib.error.HTTPError as error:
        raw, status, kind = error.read(), error.code, error.headers["Content-Type"]
    return status, json.loads(raw) if kind == "application/json" else raw


def ok(server: StudioServer, path: str, body: object = None) -> Any:
    """`call`, which must answer 200."""
    status, answer = call(server, path, body)
    assert status == 200, answer
    return answer


def settled(server: StudioServer, run: int) -> dict[str, Any]:
    """The run once its background job has ended."""
    while True:
        shown = ok(server, f"/api/figures/runs/{run}")
        if not (shown["job"] and shown["job"]["running"]):
            return shown
        time.sleep(0.2)


LOADED = "window.figures && figures.pack && !document.body.classList.contains('busy')"
"""True in the figure page once a generation is drawn and nothing is being fetched."""


def pick_and_breed(page: Any, cells: list[int], shown: int) -> list[int]:
    """Click ``cells`` of the figure page's grid and breed; wait until generation ``shown`` is
    drawn. The picks' individual ids."""
    ids: list[int] = page.evaluate(f"{cells}.map((i) => figures.pack.header.individuals[i].id)")
    for i in cells:
        page.click(f".cell[data-index='{i}']")
    page.click("#breed")
    page.wait_for_function(f"{LOADED} && figures.shown === {shown}")
    return ids


def copy_of(db: Path, folder: Path) -> Path:
    """A copy of a closed run database in ``folder``."""
    return Path(shutil.copy(db, folder / db.name))


def stored(db: Path, run: int) -> list[tuple[int, int, Any, float | None, bool]]:
    """Every individual of a run: generation, index, genome, fitness, picked."""
    with RunStore(db) as store:
        return [
            (p.generation, p.index,
             p.genome.tolist() if isinstance(p.genome, np.ndarray) else p.genome,
             p.fitness, p.picked)
            for p in store.individuals(run)
        ]  # fmt: skip


DOCS = Path(__file__).resolve().parents[1] / "docs"


def doc_shot(part: Any, shots: Path, name: str, **options: Any) -> Path:
    """Screenshot a page or an element (Playwright ``options``, e.g. ``clip``) to
    ``shots/name``; with ``SINEWS_FIGURE_DOCS`` set, also to ``docs/name`` (the figure
    studio's pictures in docs/figure-studio.md)."""
    path = shots / name
    part.screenshot(path=path, **options)
    if os.environ.get("SINEWS_FIGURE_DOCS"):
        shutil.copy(path, DOCS / name)
    return path
