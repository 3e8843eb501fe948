"""The studio tests' helpers: ``sinews studio`` in a subprocess or in process, pack decoding."""

from __future__ import annotations

import json
import queue
import signal
import struct
import subprocess
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import numpy as np
from starlette.applications import Starlette
from starlette.testclient import TestClient

from killed_runs import sinews_command
from sinews.studio.app import create_app
from sinews.studio.service import StudioSettings, Worker

CHROMIUM = Path("/usr/bin/chromium")
CHROMIUM_ARGS = [
    "--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
    "--disable-component-update", "--no-first-run", "--disable-sync", "--disable-quic",
]  # fmt: skip
DATA = Path(__file__).resolve().parent / "data"
START_TIMEOUT = 90.0
HOME = "http://127.0.0.1:8765"

INK = """(selector) => [...document.querySelectorAll(selector)].map((canvas) => {
  const data = canvas.getContext("2d").getImageData(0, 0, canvas.width, canvas.height).data;
  const off = (k, [r, g, b]) => Math.abs(data[k] - r) + Math.abs(data[k + 1] - g)
    + Math.abs(data[k + 2] - b);
  let ink = 0;  // pixels that are neither paper nor ground
  for (let k = 0; k < data.length; k += 4) {
    if (off(k, [250, 248, 243]) > 80 && off(k, [232, 228, 219]) > 80) ink++;
  }
  return { ink, picture: canvas.toDataURL() };
})"""
"""JS: for each canvas matching a selector, its pixels that are neither paper nor ground
("ink") and its picture as a data URL."""


class StudioServer:
    """``sinews studio`` in a subprocess; ``url`` once it listens."""

    def __init__(self, db: Path, env: dict[str, str], *args: str) -> None:
        self.db = db
        command = [*sinews_command(), "studio", "--no-browser", "--port", "0"]
        self.process = subprocess.Popen(
            [*command, "--db", str(db), *args],
            env=env,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
        )
        self.output: list[str] = []
        lines: queue.Queue[str] = queue.Queue()
        self._reader = threading.Thread(target=self._read, args=(lines,), daemon=True)
        self._reader.start()
        self.url = self._wait_for_url(lines)

    def _read(self, lines: queue.Queue[str]) -> None:
        assert self.process.stdout is not None
        for line in self.process.stdout:
            self.output.append(line)
            lines.put(line)

    def _wait_for_url(self, lines: queue.Queue[str]) -> str:
        while True:
            try:
                line = lines.get(timeout=START_TIMEOUT)
            except queue.Empty:
                self.kill()
                raise RuntimeError("the studio did not start:\n" + "".join(self.output)) from None
            if "http://" in line:
                return "http://" + line.split("http://", 1)[1].split()[0]

    @property
    def run_id(self) -> int:
        """The run the server opened (from its start-up line)."""
        first = next(line for line in self.output if "(run " in line)
        return int(first.split("(run ", 1)[1].split(",")[0])

    def wait(self, timeout: float) -> int:
        """The exit status, once the process has ended and all its output is read."""
        status = self.process.wait(timeout=timeout)
        self._reader.join(timeout=timeout)
        return status

    def kill(self) -> None:
        """SIGKILL: nothing gets a chance to clean up."""
        self.process.send_signal(signal.SIGKILL)
        self.process.wait(timeout=30)

    def stop(self) -> None:
        """Ctrl+C, as a person would."""
        if self.process.poll() is None:
            self.process.send_signal(signal.SIGINT)
            try:
                self.process.wait(timeout=30)
            except subprocess.TimeoutExpired:
                self.kill()


@contextmanager
def in_process_studio(db: Path) -> Iterator[TestClient]:
    """A started studio on ``db`` behind Starlette's test client (no server, no browser)."""
    worker = Worker(StudioSettings(db=db))
    worker.call(lambda s: s.start())
    with TestClient(create_app(worker), base_url=HOME) as client:
        yield client


def worker_of(client: TestClient) -> Worker:
    """The worker behind an in-process studio (the app keeps it in its state)."""
    app = client.app
    assert isinstance(app, Starlette)
    worker = app.state.worker
    assert isinstance(worker, Worker)
    return worker


def decode_pack(data: bytes) -> tuple[dict[str, Any], dict[str, np.ndarray]]:
    """The Python twin of static/js/pack.js."""
    assert data[:4] == b"SNWP"
    (length,) = struct.unpack("<I", data[4:8])
    header = json.loads(data[8 : 8 + length])
    base = 8 + length
    arrays = {}
    for name, spec in header["arrays"].items():
        assert (base + spec["offset"]) % 8 == 0
        count = int(np.prod(spec["shape"]))
        arrays[name] = np.frombuffer(
            data, dtype=np.dtype(spec["dtype"]).newbyteorder("<"), count=count,
            offset=base + spec["offset"],
        ).reshape(spec["shape"])  # fmt: skip
    return header, arrays
