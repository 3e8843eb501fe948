"""Compile the dance kernels in a second process while the studio starts.

On an empty numba cache the engine's kernels take seconds to compile, and the
studio used to compile them only after printing its address, when the first
generation was simulated. `Warmup()` launches ``python -m sinews.dancers.warmup``,
which dances two dancers for half a second to a steady beat, so numba compiles
(or loads) exactly the kernels the first generation calls and writes them to
its cache, on the other core, while the studio itself imports, makes the demo
song and analyses it. `Warmup.wait` is called before the first generation is
simulated, which then loads the kernels from the cache. When the cache already
holds them (`kernels_cached`), nothing is started and nothing waits.
"""

from __future__ import annotations

import contextlib
import os
import pickle
import subprocess
import sys
import threading
import time
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from sinews.music import MusicFeatures

__all__ = ["DANCE_KERNELS", "WAIT_SECONDS", "Warmup", "kernels_cached", "main"]

DANCE_KERNELS = ("actuate", "_simulate_body", "simulate_serial")
"""The `sinews.springmass.kernels` a dance of up to `SERIAL_BODIES` dancers compiles."""

WAIT_SECONDS = 120.0
"""Longest the studio waits for the warm-up before compiling the kernels itself."""


def kernels_cached() -> bool:
    """Whether numba's cache holds every one of `DANCE_KERNELS`, fresh for this source."""
    from sinews.springmass import kernels

    try:  # numba's own index check: present, same numba, same source stamp
        return all(
            getattr(kernels, name)._cache._cache_file._load_index() for name in DANCE_KERNELS
        )
    except (AttributeError, OSError, EOFError, ValueError, pickle.UnpicklingError):
        return False  # caching off, or an index it cannot read: warm up to be safe


class Warmup:
    """The warm-up process, started unless the kernels are cached already."""

    def __init__(self) -> None:
        self._process: subprocess.Popen[bytes] | None = None
        if kernels_cached():
            return
        with contextlib.suppress(OSError):  # none spawned: the studio compiles them itself
            self._process = subprocess.Popen(
                [sys.executable, "-m", "sinews.dancers.warmup", str(os.getpid())],
                stdin=subprocess.DEVNULL,
                stdout=subprocess.DEVNULL,
                stderr=subprocess.DEVNULL,
            )

    def wait(self) -> None:
        """Block until the kernels are in the cache (or the warm-up gave up)."""
        if self._process is None:
            return
        try:
            self._process.wait(WAIT_SECONDS)
        except subprocess.TimeoutExpired:
            self.stop()

    def stop(self) -> None:
        """End the warm-up if it is still running."""
        if self._process is not None and self._process.poll() is None:
            self._process.kill()
            self._process.wait()


def main(parent: int) -> None:
    """Dance two dancers for 0.5 s to a steady 120 BPM beat; stop if ``parent`` ends."""
    threading.Thread(target=_exit_with, args=(parent,), daemon=True).start()
    from sinews.experiments.dancers.simulate import dance, random_genomes

    dance(random_genomes(0, 2), 0.5, music=_steady_beat(0.5))


def _exit_with(parent: int) -> None:
    while os.getppid() == parent:  # an orphan is handed to another parent
        time.sleep(0.2)
    os._exit(0)  # the studio is gone (even SIGKILLed): nothing is left running


def _steady_beat(seconds: float) -> MusicFeatures:
    """A silent song with beats every 0.5 s, at the dancers' frame rate."""
    from sinews.dancers import DANCER_ENGINE
    from sinews.music import MusicFeatures
    from sinews.music.spectrum import DEFAULT_BANDS, band_centres, band_edges

    fps = 1.0 / DANCER_ENGINE.dt
    frames = round(seconds * fps)
    levels = np.zeros((frames, DEFAULT_BANDS), np.float32)
    triggers = np.zeros(levels.shape, bool)
    triggers[:: round(0.5 * fps)] = True
    beats = np.arange(0.0, seconds + 1.0, 0.5)
    edges = band_edges(DEFAULT_BANDS)
    return MusicFeatures(
        fps=fps,
        duration=seconds,
        band_edges_hz=edges,
        band_centres_hz=band_centres(edges),
        levels=levels,
        onset=levels.copy(),
        triggers=triggers,
        activation=triggers.astype(np.float32),
        tempo_bpm=120.0,
        beats=beats,
        beat_phase=((np.arange(frames) / fps / 0.5) % 1.0).astype(np.float32),
        song_hash="warmup",
    )


if __name__ == "__main__":
    main(int(sys.argv[1]))
