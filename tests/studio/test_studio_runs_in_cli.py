"""A run bred in the studio, seen from the installed ``sinews``: picks, not fitness."""

from __future__ import annotations

import json
import subprocess
from pathlib import Path

from killed_runs import sinews_command
from sinews.studio.service import StudioSettings, Worker


def test_a_studio_run_reads_well_in_the_cli(
    tmp_path: Path, studio_home: None, studio_env: dict[str, str]
) -> None:
    db = tmp_path / "studio.db"
    worker = Worker(StudioSettings(db=db))
    try:
        run = worker.call(lambda s: s.start())
        worker.call(lambda s: s.runs.breed(run, 0, [1, 3], mutation=0.2))
        worker.call(lambda s: s.runs.breed(run, 1, [2], mutation=0.2))
        latest = worker.call(lambda s: s.store.picks(run)[-1].id)
    finally:
        worker.close()

    def sinews(*args: str) -> subprocess.CompletedProcess[str]:
        env = {**studio_env, "COLUMNS": "200"}
        command = [*sinews_command(), *args, "--db", str(db)]
        return subprocess.run(command, capture_output=True, text=True, env=env, timeout=120)

    listed = sinews("runs", "list")
    assert listed.returncode == 0, listed.stderr
    row = next(line for line in listed.stdout.splitlines() if f"│ {run} " in line)
    assert "by hand" in row and "100000" not in row and "demo:groove" in row
    shown = sinews("runs", "show", str(run))
    assert shown.returncode == 0, shown.stderr
    assert "1: " in shown.stdout and "3: " in shown.stdout
    assert f"latest pick: individual {latest}" in shown.stdout
    best = sinews("runs", "best", str(run), "-o", str(tmp_path / "dancer.json"))
    assert best.returncode == 0, best.stderr
    assert f"individual {latest}," in best.stdout
    assert json.loads((tmp_path / "dancer.json").read_text())["kind"] == "sinews.dancer"
    plot = sinews("plot", str(run), "-o", str(tmp_path / "p.png"))
    assert plot.returncode == 2 and plot.stderr.count("\n") == 1 and "bred by hand" in plot.stderr
