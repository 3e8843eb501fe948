"""The run files in docs/gp work with the command their header shows (users copy them)."""

from __future__ import annotations

import shlex
import subprocess
import tomllib
from pathlib import Path

import pytest

pytest.importorskip("mujoco")

from killed_runs import sinews_command
from sinews.cli import main
from sinews.store import RunStore

RUN_FILES = sorted((Path(__file__).parents[3] / "docs" / "gp").glob("*.toml"))


def _command(path: Path) -> list[str]:
    """The ``sinews evolve ...`` line of the file's header, without the program name."""
    (line,) = [row for row in path.read_text().splitlines() if "sinews evolve" in row]
    words = shlex.split(line.lstrip("#"))
    assert words[:2] == ["sinews", "evolve"] and "--config" in words
    return words[1:]


def test_there_are_run_files() -> None:
    assert len(RUN_FILES) >= 5


@pytest.mark.parametrize("path", RUN_FILES, ids=lambda path: path.name)
def test_a_documented_run_file_makes_a_run(path: Path, tmp_path: Path) -> None:
    """Its header's command, shrunk to 4 programs x 2 generations, runs with its settings."""
    db = tmp_path / "runs.db"
    command = _command(path)
    command[command.index("--config") + 1] = str(path)
    assert main([*command, "--population", "4", "--generations", "2", "--db", str(db)]) == 0
    with RunStore(db) as store:
        (info,) = store.runs()
        assert info.status == "finished"
        options, fitness = info.config["strategy"]["options"], info.config["fitness"]
        settings = tomllib.loads(path.read_text())
        strategy = settings.get("strategy", {})
        assert options == {k: v for k, v in strategy.items() if k != "name"}
        assert fitness.get("constraints", []) == settings.get("constraints", [])


@pytest.mark.parametrize(
    ("table", "message"),
    [
        ("tweak_scale = 1e308", "tweak_scale must be in (0, 10]"),
        ("tweak_scale = nan", "tweak_scale must be in (0, 10]"),
        ("tweak_rate = 0.5", "must be >= 0 and sum to <= 1"),
        ("max_depth = 2.5", "max_depth must be a whole number, got 2.5"),
        ("tournament_size = 2.5", "tournament_size must be a whole number"),
        ("elites = true", "elites must be a whole number, got True"),
        ('crossover_rate = "x"', "crossover_rate must be a number"),
        ('init_depth = ["a", 2]', "init_depth must be (min, max)"),
    ],
)
def test_bad_variations_in_a_run_file_are_one_line_errors(
    table: str, message: str, tmp_path: Path
) -> None:
    """Through the installed ``sinews``: exit 2, one line, and no run made."""
    config, db = tmp_path / "bad.toml", tmp_path / "runs.db"
    config.write_text(f'[strategy]\nname = "gp"\n{table}\n')
    args = ["evolve", "humanoid", "--controller", "gp", "--task", "nose", "--population", "4",
            "--config", str(config), "--db", str(db)]  # fmt: skip
    done = subprocess.run([*sinews_command(), *args], capture_output=True, text=True, timeout=120)
    assert done.returncode == 2 and done.stderr.count("\n") == 1 and message in done.stderr
    with RunStore(db) as store:
        assert store.runs() == []
