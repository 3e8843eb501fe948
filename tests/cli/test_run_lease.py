"""Two processes never evolve one run: `sinews runs resume` of a run another process is
running is refused in one line (exit 2), and once that process is killed it resumes."""

from __future__ import annotations

import os
import signal
import subprocess
import time
from pathlib import Path

import pytest

from killed_runs import sinews_command, stored_generations


def test_a_run_in_progress_cannot_be_resumed_twice(tmp_path: Path) -> None:
    db = tmp_path / "runs.db"
    env = {**os.environ, "XDG_DATA_HOME": str(tmp_path / "d"), "XDG_CACHE_HOME": str(tmp_path)}
    evolve = ["evolve", "snake", "--population", "5", "--generations", "50000", "--seconds",
              "0.3", "--db", str(db)]  # fmt: skip
    first = subprocess.Popen([*sinews_command(), *evolve], env=env,
                             stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)  # fmt: skip
    try:
        while stored_generations(db) < 2:
            assert first.poll() is None, "the run ended before the test could resume it"
            time.sleep(0.05)
        resume = [*sinews_command(), "runs", "resume", "1", "--generations", "100000",
                  "--db", str(db)]  # fmt: skip
        second = subprocess.run(resume, env=env, capture_output=True, text=True, timeout=300)
        assert second.returncode == 2
        assert second.stderr.splitlines() == ["error: run 1 is being run by another process"]
        assert first.poll() is None  # the first run goes on undisturbed
    finally:
        first.send_signal(signal.SIGKILL)
        first.wait(timeout=60)
    before = stored_generations(db)
    resumed = subprocess.Popen(resume, env=env, stdout=subprocess.DEVNULL,
                               stderr=subprocess.PIPE, text=True)  # fmt: skip
    try:
        while stored_generations(db) <= before:  # the killed run's lease is free
            if resumed.poll() is not None:
                pytest.fail(f"the resume ended: {resumed.communicate()[1]}")
            time.sleep(0.05)
    finally:
        resumed.send_signal(signal.SIGINT)
        resumed.wait(timeout=120)
