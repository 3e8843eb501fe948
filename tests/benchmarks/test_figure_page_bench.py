"""``sinews bench studio``'s figure page case runs: a real studio, Chromium, two CLI runs."""

from __future__ import annotations

import pytest

from sinews.benchmarks._figure_page import figure_page
from sinews.benchmarks._measure import Measurement


@pytest.mark.slow  # ~30 s at load 7: a studio, Chromium and two `sinews evolve` processes
def test_the_figure_page_bench_breeds_shows_and_clicks() -> None:
    found = figure_page("tiny")
    cases = [m for m in found if isinstance(m, Measurement)]
    if len(cases) != len(found):
        pytest.skip(f"{found[0]}")  # no Chromium or no Playwright here
    assert len(cases) == 3
    assert [m.unit for m in cases] == ["generations/s", "generations/s", "inputs/s"]
    assert all(m.ours > 0 and m.reference > 0 for m in cases)
    assert "scoring" in cases[1].case and "idle" in cases[2].case
