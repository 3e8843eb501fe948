"""``sinews evolve``, ``sinews runs``, ``sinews render`` and ``sinews plot`` end to end."""

from __future__ import annotations

import csv
from pathlib import Path

import pytest
from PIL import Image

from sinews.cli import main
from sinews.dancers import DancerGenome
from sinews.store import RunStore

SONG = str(Path(__file__).resolve().parents[1] / "data" / "loop_mika.flac")


@pytest.fixture(autouse=True)
def _private_dirs(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("XDG_DATA_HOME", str(tmp_path / "data"))
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))


def run(capsys: pytest.CaptureFixture[str], *args: str) -> tuple[int, str, str]:
    status = main(list(args))
    out, err = capsys.readouterr()
    return status, out, err


@pytest.fixture
def db(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> Path:
    path = tmp_path / "runs.db"
    status, out, err = run(
        capsys, "evolve", "dancers", "--song", SONG, "--population", "4", "--generations", "3",
        "--seconds", "2", "--seed", "2", "--fitness", "beat-align,liveliness",
        "--weights", "liveliness=0.05", "--phase-in", "1:2", "--executor", "serial",
        "--db", str(path),
    )  # fmt: skip
    assert status == 0, err
    assert "run 1" in err and "generation 3/3" in err
    assert "beat-align" in out and "best: individual" in out
    return path


def test_runs_list_show_best_lineage_export(
    db: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    status, out, _ = run(capsys, "runs", "list", "--db", str(db))
    assert status == 0 and "finished" in out and "3/3" in out
    assert "…" not in out  # nothing cut at 80 columns, the creation time to the minute
    status, out, _ = run(capsys, "runs", "show", "1", "--db", str(db))
    assert status == 0 and '"liveliness": 0.05' in out and "loop_mika.flac" in out
    status, out, _ = run(
        capsys, "runs", "best", "1", "-o", str(tmp_path / "d.json"), "--db", str(db)
    )
    assert status == 0
    with RunStore(db) as store:
        best = store.best(1)
    assert DancerGenome.load(tmp_path / "d.json") == DancerGenome(best.genome)
    status, out, _ = run(capsys, "runs", "lineage", str(best.id), "--db", str(db))
    assert status == 0 and f" {best.id} " in out
    assert any(line.split("│")[2].strip() == "0" for line in out.splitlines() if "│" in line)
    status, out, _ = run(capsys, "runs", "export", "1", "-o", str(tmp_path / "x"), "--db", str(db))
    assert status == 0
    with open(tmp_path / "x" / "individuals.csv") as fh:
        assert len(list(csv.DictReader(fh))) == 12


def test_render_and_plot(db: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    picture = tmp_path / "best.png"
    status, _, err = run(capsys, "render", "1", "--best", "-o", str(picture), "--size", "120",
                           "--db", str(db))  # fmt: skip
    assert status == 0, err
    assert Image.open(picture).size[0] == 120
    video = tmp_path / "first.mp4"
    status, _, err = run(capsys, "render", "1", "--individual", "1", "-o", str(video), "--size",
                         "96", "--db", str(db))  # fmt: skip
    assert status == 0, err
    assert video.stat().st_size > 1000
    plot = tmp_path / "fitness.png"
    status, _, err = run(capsys, "plot", "1", "-o", str(plot), "--db", str(db))
    assert status == 0, err
    assert Image.open(plot).format == "PNG"
    with RunStore(db) as store:
        assert [m.kind for m in store.media(1)] == ["png", "mp4", "png"]


def test_resume_of_a_finished_run_says_so(db: Path, capsys: pytest.CaptureFixture[str]) -> None:
    status, _, err = run(capsys, "runs", "resume", "1", "--executor", "serial", "--db", str(db))
    assert status == 0 and "run 1 is finished (3 generations)" in err
    status, _, err = run(capsys, "runs", "resume", "1", "--generations", "4", "--executor",
                         "serial", "--db", str(db))  # fmt: skip
    assert status == 0 and "generation 4/4" in err


def test_a_run_file_is_read(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    config = tmp_path / "run.toml"
    config.write_text(f'song = "{SONG}"\npopulation = 3\ngenerations = 1\nseconds = 1.5\n'
                      '[strategy]\nname = "ga"\nmutation_sigma = 0.2\n')  # fmt: skip
    status, _, err = run(capsys, "evolve", "dancers", "--config", str(config), "--executor",
                         "serial", "--db", str(tmp_path / "r.db"))  # fmt: skip
    assert status == 0, err
    with RunStore(tmp_path / "r.db") as store:
        info = store.run(1)
    assert info.config["population"] == 3 and info.config["seconds"] == 1.5
    assert info.config["strategy"] == {"name": "ga", "options": {"mutation_sigma": 0.2}}


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["evolve", "dancers", "--song", SONG, "--fitness", "grace"], "no fitness term"),
        (["evolve", "dancers", "--song", "demo:polka"], "no demo song 'polka'"),
        (["evolve", "dancers", "--song", SONG, "--executor", "gpu"], "no executor called"),
        (["runs", "show", "9"], "no such run database"),  # read commands create nothing
        (["render", "1", "-o", "x.png"], "either --individual ID or --best"),
        (["plot", "3", "-o", "x.png"], "no run 3"),
    ],
)
def test_user_errors_are_one_line(
    args: list[str], message: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    status, _, err = run(capsys, *args, "--db", str(tmp_path / "runs.db"))
    assert status == 2
    assert err.startswith("error: ") and message in err and err.count("\n") == 1


def test_a_corrupt_database_is_refused_and_kept(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    path = tmp_path / "runs.db"
    path.write_bytes(b"\x00garbage" * 100)
    status, _, err = run(capsys, "runs", "list", "--db", str(path))
    assert status == 2 and "not a sinews database" in err and err.count("\n") == 1
    assert path.read_bytes() == b"\x00garbage" * 100
