"""The studio's kernel warm-up: it compiles what a generation needs and dies with the studio."""

from __future__ import annotations

import os
import subprocess
import sys
import time
from pathlib import Path

CACHED = "from sinews.dancers.warmup import kernels_cached; print(kernels_cached())"

# what the studio's first generation does: 16 dancers to an analysed song
GENERATION = """
from sinews.experiments.dancers.simulate import dance, random_genomes
from sinews.music import Audio, analyse, demo_song
song = demo_song()
music = analyse(Audio(song.samples[: 8 * song.sample_rate].mean(axis=1), song.sample_rate))
dance(random_genomes(1, 16), 4.0, music=music, seeds=range(16))
"""


def python(code: str, env: dict[str, str]) -> str:
    done = subprocess.run(
        [sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True
    )
    return done.stdout


def test_the_warm_up_caches_every_kernel_a_studio_generation_compiles(tmp_path: Path) -> None:
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path / "numba")}
    assert python(CACHED, env).strip() == "False"
    subprocess.run(
        [sys.executable, "-m", "sinews.dancers.warmup", str(os.getpid())], env=env, check=True
    )
    assert python(CACHED, env).strip() == "True"
    log = python(GENERATION, {**env, "NUMBA_DEBUG_CACHE": "1"})
    engine = [line for line in log.splitlines() if "springmass" in line]
    assert any("index loaded" in line for line in engine)
    assert not [line for line in engine if "saved" in line]  # nothing left to compile


def test_an_orphaned_warm_up_exits(tmp_path: Path) -> None:
    """Its parent (here a shell, in use a SIGKILLed studio) is gone: it stops at once."""
    code = (
        "import sys, threading, time; from sinews.dancers import warmup; "
        "threading.Thread(target=warmup._exit_with, args=(int(sys.argv[1]),)).start(); "
        "time.sleep(600)"
    )
    shell = subprocess.run(
        ["sh", "-c", f'"{sys.executable}" -c "{code}" $$ >/dev/null & echo $!'],
        capture_output=True,
        text=True,
        check=True,
    )
    pid = int(shell.stdout)
    deadline = time.monotonic() + 60  # a liveness limit, not a timing claim: 600 s otherwise
    while _running(pid) and time.monotonic() < deadline:
        time.sleep(0.1)
    assert not _running(pid)


def _running(pid: int) -> bool:
    try:
        status = Path(f"/proc/{pid}/status").read_text()
    except FileNotFoundError:
        return False
    return "\nState:\tZ" not in status
