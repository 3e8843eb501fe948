"""The figure page in Chromium: breeding a generation of lamps, and input while a run evolves.

A real ``sinews studio`` in a subprocess on a database with a spring-net run
of the lamp (20 per generation, 5 s trials, made by ``sinews evolve``),
driven by Debian's headless Chromium through Playwright, as a person would:

- **breed**: pick two lamps, press "Next generation", and time in the page
  the breed request (the server breeds, scores the 20 children and stores
  them: the generation's *scoring time*) and then the generation's pose pack
  (the server replays the 20 and packs them) until the new grid is drawn.
  Targets (issue 17): shown < 0.5 s after scoring is done, and picking →
  shown < scoring time + 0.5 s.
- **input latency**: clicks on the replay's seek bar (its handler redraws
  the 20 cells and the stage) while the page's background run evolves the
  run and a ``sinews evolve`` of another run works in a second process (both
  cores busy), against the same clicks with nothing running. Latency is from
  the click's own timestamp (so waiting for a busy main thread counts) to the
  start of the next frame. Target < 50 ms.
"""

from __future__ import annotations

import os
import queue
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path
from typing import Any

import numpy as np

from sinews.benchmarks._measure import Measurement, Result, Scale, Skipped

__all__ = ["figure_page"]

CHROMIUM = Path("/usr/bin/chromium")
CHROMIUM_ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
                 "--disable-component-update", "--no-first-run", "--disable-sync"]  # fmt: skip
LOADED = "window.figures && figures.pack && !document.body.classList.contains('busy')"
TIMING = """() => {
  window.benchFetches = [];
  const fetchNow = window.fetch;
  window.fetch = async (url, init) => {
    const start = performance.now();
    const response = await fetchNow(url, init);
    window.benchFetches.push({ url: String(url), start, end: performance.now() });
    return response;
  };
  window.benchLatency = [];
  addEventListener("pointerdown", (event) => {
    requestAnimationFrame(() => window.benchLatency.push(performance.now() - event.timeStamp));
  }, true);
}"""
BREED = """(target) => new Promise((resolve) => {
  window.benchFetches.length = 0;
  const start = performance.now();
  const seen = new MutationObserver(() => {
    if (figures.shown !== target) return;
    seen.disconnect();
    requestAnimationFrame(() => {
      const [breed, pack] = ["/breed", `/generations/${target}`].map(
        (end) => window.benchFetches.find((f) => f.url.endsWith(end)));
      resolve({ start, breedEnd: breed.end, scoring: breed.end - breed.start,
                pack: pack.end - pack.start, shown: performance.now() });
    });
  });
  seen.observe(document.getElementById("grid"), { childList: true });
  document.getElementById("breed").click();
})"""


def _sinews(*args: str) -> list[str]:
    return [str(Path(sys.executable).with_name("sinews")), *args]


class _Studio:
    """``sinews studio`` on ``db`` in a subprocess; ``url`` once it listens."""

    def __init__(self, db: Path, env: dict[str, str]) -> None:
        command = _sinews("studio", "--no-browser", "--port", "0", "--db", str(db))
        self.process = subprocess.Popen(command, env=env, stdout=subprocess.PIPE,
                                        stderr=subprocess.STDOUT, text=True)  # fmt: skip
        lines: queue.Queue[str] = queue.Queue()
        threading.Thread(target=self._read, args=(lines,), daemon=True).start()
        while True:
            line = lines.get(timeout=300)
            if "http://" in line:
                self.url = "http://" + line.split("http://", 1)[1].split()[0]
                return

    def _read(self, lines: queue.Queue[str]) -> None:
        assert self.process.stdout is not None
        for line in self.process.stdout:
            lines.put(line)

    def stop(self) -> None:
        self.process.terminate()
        self.process.wait(timeout=60)


def _clicks(page: Any, count: int) -> list[float]:
    """Latencies (ms) of ``count`` clicks on the seek bar, 0.15 s apart."""
    box = page.locator("#seek").bounding_box()
    page.evaluate("window.benchLatency.length = 0")
    for k in range(count):
        x = box["x"] + box["width"] * (0.1 + 0.8 * ((k * 7) % count) / count)
        page.mouse.click(x, box["y"] + box["height"] / 2)
        page.wait_for_timeout(150)
    return list(page.evaluate("window.benchLatency"))


def figure_page(scale: Scale = "full") -> list[Result]:
    """Breed generations of 20 lamps (5 s trials; tiny: 5 lamps, 1 s) in the page and click
    while runs evolve."""
    case = "figure page: lamps bred and shown, input latency"
    if not CHROMIUM.exists():
        return [Skipped(case, f"needs Chromium at {CHROMIUM} (apt-get install chromium)")]
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        return [Skipped(case, "playwright is not installed (pip install 'sinews[all]')")]
    rounds, clicks, population, seconds = {"full": (3, 40, 20, 5), "quick": (2, 20, 20, 5),
                                           "tiny": (1, 5, 5, 1)}[scale]  # fmt: skip
    lamps = ["luxo", "--population", str(population), "--seconds", str(seconds)]
    with tempfile.TemporaryDirectory(prefix="sinews-bench-") as tmp:
        root = Path(tmp)
        env = {**os.environ, "XDG_DATA_HOME": str(root / "data"),
               "XDG_CACHE_HOME": str(root / "cache")}  # fmt: skip
        db = root / "studio.db"
        made = _sinews("evolve", *lamps, "--generations", "1", "--seed", "1", "--db", str(db))
        subprocess.run(made, env=env, check=True, capture_output=True)
        server = _Studio(db, env)
        other: subprocess.Popen[bytes] | None = None
        try:
            with sync_playwright() as playwright:
                browser = playwright.chromium.launch(executable_path=str(CHROMIUM),
                                                     args=CHROMIUM_ARGS)  # fmt: skip
                page = browser.new_page(viewport={"width": 1600, "height": 1000})
                page.goto(f"{server.url}figures?run=1")
                page.wait_for_function(f"{LOADED} && figures.run.id === 1", timeout=600_000)
                page.evaluate(TIMING)
                bred = []
                for generation in range(1, rounds + 1):
                    page.click(".cell[data-index='1']")
                    page.click(".cell[data-index='3']")
                    bred.append(page.evaluate(BREED, generation))
                idle = _clicks(page, clicks)
                page.fill("#more", "100")
                page.click("#evolve")
                other = subprocess.Popen(
                    _sinews("evolve", *lamps, "--generations", "1000", "--seed", "2",
                            "--db", str(db)),
                    env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                )  # fmt: skip
                page.wait_for_function("figures.run.job && figures.run.job.running")
                time.sleep(2.0)  # both at work
                busy = _clicks(page, clicks)
                load = os.getloadavg()[0]
                page.click("#pause")
                browser.close()
        finally:
            if other is not None:
                other.terminate()
                other.wait(timeout=120)
            server.stop()
    return _results(f"{population} lamps × {seconds} s", bred, idle, busy, load)


def _results(
    lamps: str, bred: list[dict[str, float]], idle: list[float], busy: list[float], load: float
) -> list[Result]:
    scoring = float(np.median([b["scoring"] for b in bred]))
    after = float(np.median([b["shown"] - b["breedEnd"] for b in bred]))
    total = float(np.median([b["shown"] - b["start"] for b in bred]))
    pack = float(np.median([b["pack"] for b in bred]))
    quiet, loaded = float(np.median(idle)), float(np.median(busy))
    worst = float(np.percentile(busy, 95))
    return [
        Measurement(
            f"figure page: scoring done → next generation drawn, {lamps} "
            f"({after:.0f} ms, of it the pose pack {pack:.0f} ms; median of {len(bred)})",
            "generations/s",
            1000 / after,
            1000 / 500,
            "the target, 0.5 s",
        ),
        Measurement(
            f"figure page: picks → next generation drawn ({total:.0f} ms; scoring "
            f"{scoring:.0f} ms)",
            "generations/s",
            1000 / total,
            1000 / (scoring + 500),
            f"the target, scoring + 0.5 s ({scoring + 500:.0f} ms)",
        ),
        Measurement(
            f"figure page: click → next frame while a page run and a CLI run evolve (median "
            f"{loaded:.0f} ms, 95th percentile {worst:.0f} ms, load {load:.1f}; idle "
            f"{quiet:.0f} ms)",
            "inputs/s",
            1000 / loaded,
            1000 / 50,
            "the target, 50 ms",
        ),
    ]
