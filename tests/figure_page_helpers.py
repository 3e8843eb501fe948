"""The figure page's tests' helpers: the installed ``sinews`` on a database, the page's API
called over HTTP, a run's individuals as stored."""

from __future__ import annotations

import json
import subprocess
import urllib.error
import urllib.request
from pathlib import Path
from typing import Any

import numpy as np

from killed_runs import sinews_command
from sinews.store import RunStore
from studio_helpers import StudioServer

__all__ = ["call", "ok", "sinews", "stored"]


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
    status, answer = call(server, path, body)
    assert status == 200, answer
    return answer


def stored(db: Path, run: int) -> list[tuple[int, int, Any, float | None, bool]]:
    """Every individual of a run: generation, index, genome, fitness, picked."""
    with RunStore(db) as store:
        return [
            (p.generation, p.index,
             p.genome.tolist() if isinstance(p.genome, np.ndarray) else p.genome,
             p.fitness, p.picked)
            for p in store.individuals(run)
        ]  # fmt: skip
