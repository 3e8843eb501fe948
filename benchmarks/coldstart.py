"""Cold start: `sinews studio` to its first generation served, and a first `sinews dance`.

Run: ``python benchmarks/coldstart.py [--repeats 2]`` (BENCHMARKS.md, "Cold start").

For an empty numba cache (``NUMBA_CACHE_DIR`` pointing at a fresh folder, so every
kernel compiles) and then a warm one (the same folder again), each measured
``--repeats`` times alternately with fresh data folders:

- ``studio ready``: from starting ``sinews studio --no-browser`` (bundled demo
  song, 16 dancers) to its printing the address;
- ``first pack``: from the same start to the end of ``GET`` of generation 0's
  pack, which is what the page fetches to play the first generation (a proxy
  for "playing": the page's own decoding and first frame come on top, tens of
  ms in Chromium);
- ``first dance``: the whole ``sinews dance GENOME -o out.png --song demo:groove
  --seconds 8`` process (analysis, simulation, drawing);
- ``import``: ``python -c "import sinews.cli"``, the floor under both;
- ``second start`` (warm only): ``sinews studio`` again on the same data folder, as
  a returning user starts it: the demo song and its analysis are kept, so this is
  imports, loading the cached kernels and simulating generation 0.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
import urllib.request
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))  # studio_helpers

from killed_runs import sinews_command
from studio_helpers import StudioServer


def studio(env: dict[str, str], root: Path) -> tuple[float, float]:
    """Seconds to the address, and to generation 0's pack fetched."""
    started = time.perf_counter()
    server = StudioServer(root / "studio.db", env)
    try:
        ready = time.perf_counter() - started
        url = f"{server.url.rstrip('/')}/api/runs/{server.run_id}/generations/0"
        with urllib.request.urlopen(url, timeout=900) as answer:
            answer.read()
        return ready, time.perf_counter() - started
    finally:
        server.stop()


def timed(command: list[str], env: dict[str, str], cwd: Path) -> float:
    started = time.perf_counter()
    subprocess.run(command, env=env, cwd=cwd, check=True, capture_output=True, timeout=900)
    return time.perf_counter() - started


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--repeats", type=int, default=2)
    args = parser.parse_args()
    sinews = sinews_command()
    with tempfile.TemporaryDirectory(prefix="sinews-cold-") as cache:
        for state in ("empty", "warm"):
            for repeat in range(args.repeats if state == "warm" else 1):
                with tempfile.TemporaryDirectory() as folder:
                    root = Path(folder)
                    env = {
                        **os.environ,
                        "XDG_DATA_HOME": str(root / "data"),
                        "XDG_CACHE_HOME": str(root / "cache"),
                        "NUMBA_CACHE_DIR": cache,
                    }
                    ready, pack = studio(env, root)
                    subprocess.run(
                        [*sinews, "dancer", "new", "-o", "g.json"],
                        env=env,
                        cwd=root,
                        check=True,
                        capture_output=True,
                    )
                    dance = timed(
                        [
                            *sinews,
                            "dance",
                            "g.json",
                            "-o",
                            "d.png",
                            "--song",
                            "demo:groove",
                            "--seconds",
                            "8",
                        ],
                        env,
                        root,
                    )
                    floor = timed([sys.executable, "-c", "import sinews.cli"], env, root)
                    print(
                        f"{state} cache (run {repeat + 1}): studio ready {ready:.1f} s, "
                        f"first pack {pack:.1f} s, first dance {dance:.1f} s, "
                        f"import {floor:.2f} s",
                        flush=True,
                    )
                    if state == "warm":  # the same user again: song and analysis kept
                        ready, pack = studio(env, root)
                        print(f"  second start: studio ready {ready:.1f} s, first pack "
                              f"{pack:.1f} s", flush=True)  # fmt: skip
                if state == "empty":
                    size = sum(f.stat().st_size for f in Path(cache).rglob("*") if f.is_file())
                    print(f"numba cache after the first run: {size / 2**20:.1f} MB", flush=True)


if __name__ == "__main__":
    main()
