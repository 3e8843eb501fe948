"""Measure a studio server making a 6-minute generation pack (BENCHMARKS.md, "Studio: whole songs").

Run: ``python benchmarks/studio/long_song.py [--population 20] [--seconds 360]``.
Starts ``sinews studio`` in a subprocess on a generated song (clicks at
120 BPM over quiet noise), fetches the first generation's pack and prints its
size, the time to make it and the server's peak resident memory (VmHWM).
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
import urllib.request
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tests"))  # studio_helpers

from sinews.music import save_wav
from studio_helpers import StudioServer

RATE = 22_050


def click_song(path: Path, seconds: float, bpm: float = 120.0) -> Path:
    """A cheap song: a decaying click on every beat over quiet noise."""
    rng = np.random.default_rng(0)
    samples = (0.01 * rng.standard_normal(int(seconds * RATE))).astype(np.float32)
    click = (0.8 * np.exp(-np.arange(2000) / 300.0)).astype(np.float32)
    for start in np.arange(0.0, seconds - 0.2, 60.0 / bpm):
        k = int(start * RATE)
        samples[k : k + len(click)] += click
    return save_wav(path, samples, RATE)


def status(pid: int, field: str) -> float:
    """A /proc/PID/status memory field, in MB."""
    for line in Path(f"/proc/{pid}/status").read_text().splitlines():
        if line.startswith(field + ":"):
            return int(line.split()[1]) / 1024
    raise KeyError(field)


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--population", type=int, default=20)
    parser.add_argument("--seconds", type=float, default=360.0)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        root = Path(folder)
        env = {**os.environ, "XDG_DATA_HOME": str(root / "data"),
               "XDG_CACHE_HOME": str(root / "cache")}  # fmt: skip
        song = click_song(root / "long.wav", args.seconds)
        started = time.perf_counter()
        server = StudioServer(
            root / "studio.db", env, "--song", str(song), "--population", str(args.population)
        )
        try:
            first = time.perf_counter() - started
            pid = server.process.pid
            before = status(pid, "VmRSS")
            started = time.perf_counter()
            url = f"{server.url.rstrip('/')}/api/runs/{server.run_id}/generations/0"
            with urllib.request.urlopen(url, timeout=1800) as answer:
                pack = answer.read()
            made = time.perf_counter() - started
            print(f"song {args.seconds:.0f} s, {args.population} dancers")
            print(f"server start (analysis + first generation simulated): {first:.1f} s")
            print(f"generation pack: {len(pack) / 2**20:.1f} MB in {made:.1f} s")
            print(f"server RSS before the pack {before:.0f} MB, after {status(pid, 'VmRSS'):.0f}"
                  f" MB, peak (VmHWM) {status(pid, 'VmHWM'):.0f} MB")  # fmt: skip
        finally:
            server.stop()


if __name__ == "__main__":
    main()
