"""``sinews evolve snake|luxo``, and ``runs``, ``render`` and ``plot`` on figure runs."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
from PIL import Image

pytest.importorskip("mujoco")

from sinews.cli import main
from sinews.store import RunStore

TINY = ["--population", "10", "--generations", "2", "--seconds", "0.4", "--seed", "1"]


@pytest.fixture(autouse=True)
def _private_dirs(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("XDG_DATA_HOME", str(tmp_path / "data"))
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))


def run(capsys: pytest.CaptureFixture[str], *args: str) -> tuple[int, str, str]:
    status = main(list(args))
    out, err = capsys.readouterr()
    return status, out, err


def test_evolve_show_best_render_plot_resume(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    db = str(tmp_path / "runs.db")
    keep = tmp_path / "keep.txt"
    keep.write_text("0: 2\n")
    status, out, err = run(capsys, "evolve", "snake", *TINY, "--keep", str(keep), "--db", db)
    assert status == 0, err
    assert "generation 2/2" in err and "best: individual" in out
    status, out, _ = run(capsys, "runs", "show", "1", "--db", db)
    assert status == 0 and "springnet-snake" in out and '"alton"' in out
    rows = re.findall(r"^ +(\d+) +[-\d.]+ +[-\d.]+ +\d+ *(.*?) *$", out, re.MULTILINE)
    assert "'picked'" in out and rows == [("0", "2"), ("1", "")]  # generation 0: cell 2
    status, _, err = run(capsys, "runs", "best", "1", "-o", str(tmp_path / "n.json"), "--db", db)
    assert status == 0, err
    assert json.loads((tmp_path / "n.json").read_text())["figure"] == "snake"
    status, _, err = run(capsys, "render", "1", "--best", "-o", str(tmp_path / "b.png"),
                         "--size", "160", "--db", db)  # fmt: skip
    assert status == 0, err
    assert Image.open(tmp_path / "b.png").size == (160, 120)
    status, _, err = run(capsys, "render", "1", "--generations", "all", "-o",
                         str(tmp_path / "l.mp4"), "--size", "96", "--db", db)  # fmt: skip
    assert status == 0, err
    assert (tmp_path / "l.mp4").stat().st_size > 1000
    status, _, err = run(capsys, "plot", "1", "-o", str(tmp_path / "f.png"), "--db", db)
    assert status == 0, err
    status, _, err = run(capsys, "runs", "resume", "1", "--generations", "3", "--db", db)
    assert status == 0 and "generation 3/3" in err
    with RunStore(db) as store:
        assert store.individuals(1, 0)[2].picked
        assert [m.kind for m in store.media(1)] == ["png", "mp4", "png"]


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["evolve", "luxo", "--controller", "neat"], "no controller called 'neat'"),
        (["evolve", "luxo", "--keep", "missing.txt"], "cannot read"),
        (["evolve", "snake", "--population", "4"], "at least 5"),
        (["evolve", "snake", "--masses", "1"], "masses must be"),
        (["evolve", "snake", "--population", "5", "--keep", "KEEP"], "below the population"),
    ],
)
def test_user_errors_are_one_line(
    args: list[str], message: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    (tmp_path / "keep.txt").write_text("1: 5\n")
    args = [str(tmp_path / "keep.txt") if a == "KEEP" else a for a in args]
    status, _, err = run(capsys, *args, "--db", str(tmp_path / "runs.db"))
    assert status == 2
    assert err.startswith("error: ") and message in err and err.count("\n") == 1
