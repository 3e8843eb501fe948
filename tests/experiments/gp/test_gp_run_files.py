"""The run files in docs/gp work with the command their header shows (users copy them)."""

from __future__ import annotations

import shlex
import tomllib
from pathlib import Path

import pytest

pytest.importorskip("mujoco")

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
        options = info.config["strategy"]["options"]
        strategy = tomllib.loads(path.read_text()).get("strategy", {})
        assert options == {k: v for k, v in strategy.items() if k != "name"}
