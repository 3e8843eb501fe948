"""The installed ``sinews`` script as a user meets it: exit codes, one-line errors, Ctrl-C."""

from __future__ import annotations

import os
import signal
import subprocess
import time
from pathlib import Path

import pytest

import sinews
from killed_runs import alive, descendants, sinews_command, stored_generations

PACKAGE = Path(sinews.__file__).parent


def run(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([*sinews_command(), *args], capture_output=True, text=True, timeout=120)


@pytest.mark.parametrize(
    "args",
    [
        ["nosuchcmd"],
        ["dance"],
        ["evolve", "dancers", "--population", "abc"],
        ["runs", "resume", "-1"],
        ["runs", "show", "--nosuchoption"],
    ],
)
def test_usage_errors_are_one_line_and_exit_2(args: list[str]) -> None:
    result = run(*args)
    assert result.returncode == 2
    lines = result.stderr.splitlines()
    assert len(lines) == 1, result.stderr
    assert lines[0].startswith("error: ") and "--help" in lines[0]
    assert "Traceback" not in result.stderr + result.stdout


def test_help_exits_0() -> None:
    result = run("--help")
    assert result.returncode == 0
    assert "evolve" in result.stdout


@pytest.mark.parametrize("delay", [0.0, 0.05, 0.15, 0.3])
def test_ctrl_c_while_starting_exits_130_quietly(delay: float) -> None:
    proc = subprocess.Popen([*sinews_command(), "songs", "demo", "--help"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)  # fmt: skip
    time.sleep(delay)
    proc.send_signal(signal.SIGINT)
    out, err = proc.communicate(timeout=60)
    # finished before the signal (0); killed by it before Python set up its handlers, which
    # the shell reports as 130 too (-SIGINT); or interrupted, saying so in one line (130)
    assert proc.returncode in (0, 130, -signal.SIGINT)
    assert "Traceback" not in out
    if "Traceback" in err:
        # Python's own start-up (site, the console script's `import re, sys`) can take the
        # signal on a loaded machine before any sinews code runs; from the first line of
        # sinews on, the handler in sinews/__main__.py owns it and no frame may be ours
        assert proc.returncode == -signal.SIGINT
        assert str(PACKAGE) not in err, err
    if proc.returncode == 130:
        assert err.strip().splitlines()[-1] == "interrupted"


@pytest.mark.slow
def test_ctrl_c_mid_run_exits_130_and_leaves_no_process(tmp_path: Path) -> None:
    db = tmp_path / "runs.db"
    args = ["evolve", "dancers", "--song", "demo:groove", "--population", "8", "--seconds", "3",
            "--generations", "100000", "--executor", "processes", "--workers", "2",
            "--db", str(db)]  # fmt: skip
    env = {**os.environ, "XDG_DATA_HOME": str(tmp_path / "d"), "XDG_CACHE_HOME": str(tmp_path)}
    proc = subprocess.Popen([*sinews_command(), *args], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, env=env)  # fmt: skip
    while stored_generations(db) < 2 and proc.poll() is None:
        time.sleep(0.01)
    children = descendants(proc.pid)
    assert children, "the process executor started no workers"
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=120)
    assert proc.returncode == 130
    assert "Traceback" not in err
    assert "sinews runs resume 1" in err
    for _ in range(1000):
        left = [pid for pid in children if alive(pid)]
        if not left:
            break
        time.sleep(0.01)
    assert not left, f"processes left behind: {left}"
