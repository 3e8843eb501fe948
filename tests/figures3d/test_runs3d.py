"""3D GP runs through the CLI: one seed, one run on any executor; a SIGKILLed run resumes bit
for bit; targets are checked; ``render`` draws a 3D run with MuJoCo's renderer."""

from __future__ import annotations

import importlib.util
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from PIL import Image

from gp_helpers import stored
from killed_runs import kill_when, stored_generations

pytest.importorskip("mujoco")

from sinews.cli import main
from sinews.store import RunStore

OPTIONS: dict[str, Any] = {"task": "hop", "target": "1.0,0.5", "population": 6,
                           "generations": 5, "seconds": 0.4, "seed": 3}  # fmt: skip


def arguments(figure: str = "luxo3d", **changes: Any) -> list[str]:
    options = {**OPTIONS, **changes}
    given = [part for key, value in options.items() for part in (f"--{key}", str(value))]
    return ["evolve", figure, "--controller", "gp", *given]


@pytest.fixture(scope="module")
def whole(tmp_path_factory: pytest.TempPathFactory) -> Path:
    db = tmp_path_factory.mktemp("whole3d") / "runs.db"
    assert main([*arguments(), "--db", str(db)]) == 0
    return db


def test_a_3d_run_is_stored_with_its_task(whole: Path) -> None:
    status, individuals, checkpoints = stored(whole)
    assert (status, len(individuals), len(checkpoints)) == ("finished", 30, 5)
    with RunStore(whole) as store:
        (info,) = store.runs()
    assert info.kind == "gp-luxo3d"
    assert info.config["task"] == "luxo3d-hop"
    assert info.config["task_options"]["target"] == [1.0, 0.5]


def test_an_aimed_lamp_run_keeps_its_lamp(tmp_path: Path) -> None:
    db = tmp_path / "aimed.db"
    assert main([*arguments(generations=1, lamp="aimed"), "--db", str(db)]) == 0
    with RunStore(db) as store:
        (info,) = store.runs()
    assert info.config["task_options"] == {"target": [1.0, 0.5], "lamp": "aimed"}
    assert len(stored(db)[1]) == 6


@pytest.mark.parametrize(
    "executor",
    [
        "processes",
        pytest.param(
            "dask",
            marks=pytest.mark.skipif(
                importlib.util.find_spec("distributed") is None, reason="dask not installed"
            ),
        ),
    ],
)
def test_the_same_seed_gives_the_same_3d_run_on_any_executor(
    whole: Path, tmp_path: Path, executor: str
) -> None:
    pool = tmp_path / "pool.db"
    assert main([*arguments(), "--executor", executor, "--workers", "2", "--db", str(pool)]) == 0
    assert stored(pool) == stored(whole)


def test_a_killed_3d_run_resumes_to_the_uninterrupted_one(whole: Path, tmp_path: Path) -> None:
    cut = tmp_path / "cut.db"
    kill_when([*arguments(), "--db", str(cut)], cut, 2)
    assert 2 <= stored_generations(cut) < 5
    assert main(["runs", "resume", "1", "--db", str(cut)]) == 0
    assert stored(cut) == stored(whole)


@pytest.mark.parametrize(
    ("figure", "changes", "message"),
    [
        ("luxo3d", {"target": "1.0"}, "X,Y in m"),
        ("humanoid3d", {"task": "touch", "target": "0.5,1.2"}, "X,Y,Z in m"),
        ("humanoid3d", {"task": "gesture", "target": "1,2,3"}, "has no --target"),
        ("humanoid3d", {"task": "hop"}, "choose from point, gesture, touch, nose"),
        ("luxo", {"target": "1.0", "lamp": "aimed"}, "--lamp is for the 3D lamp's hop and limbo"),
        ("luxo3d", {"lamp": "glass"}, "the lamp is twist or aimed, not 'glass'"),
    ],
)
def test_bad_3d_targets_are_one_line(
    figure: str,
    changes: dict[str, Any],
    message: str,
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
) -> None:
    assert main([*arguments(figure, **changes), "--db", str(tmp_path / "x.db")]) == 2
    err = capsys.readouterr().err.strip()
    assert message in err and "\n" not in err


def test_spring_nets_of_3d_figures_are_refused_in_one_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["evolve", "luxo3d", "--population", "5", "--db", str(tmp_path / "x.db")]) == 2
    err = capsys.readouterr().err.strip()
    assert "spring nets drive the snake, luxo, humanoid" in err and "\n" not in err


def test_render_draws_a_3d_run_with_mujoco(whole: Path, tmp_path: Path) -> None:
    from sinews.render.mujoco_view import GLBackendError, _context_class, gl_backend

    try:
        _context_class(gl_backend())
    except GLBackendError as exc:
        pytest.skip(str(exc))
    path = tmp_path / "best.png"
    assert main(["render", "1", "--best", "-o", str(path), "--size", "320",
                 "--db", str(whole)]) == 0  # fmt: skip
    image = np.asarray(Image.open(path))
    assert image.shape == (180, 320, 3) and image.std() > 10
