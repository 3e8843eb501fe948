"""``sinews bench studio`` measures the figure page: a real studio, Chromium, two CLI runs.

Run as the installed ``sinews`` in a subprocess (Playwright's sync API cannot start inside
another test's running Playwright)."""

from __future__ import annotations

import subprocess

import pytest

from killed_runs import sinews_command
from studio_helpers import CHROMIUM


@pytest.mark.slow  # ~30 s at load 10: a studio, Chromium and two `sinews evolve` processes
def test_sinews_bench_studio_breeds_shows_and_clicks_in_the_figure_page(
    studio_env: dict[str, str],
) -> None:
    if not CHROMIUM.exists():
        pytest.skip(f"needs Chromium at {CHROMIUM}")
    done = subprocess.run([*sinews_command(), "bench", "studio", "--scale", "tiny"],
                          env={**studio_env, "COLUMNS": "400"}, capture_output=True, text=True,
                          timeout=900)  # fmt: skip
    assert done.returncode == 0, done.stderr
    rows = [line for line in done.stdout.splitlines() if "figure page" in line]
    assert len(rows) == 3, done.stdout
    assert "scoring done → next generation drawn, 5 lamps × 1 s" in rows[0]
    assert "picks → next generation drawn" in rows[1] and "scoring" in rows[1]
    assert "click → next frame" in rows[2] and "idle" in rows[2]
    assert all("generations/s" in row or "inputs/s" in row for row in rows)
