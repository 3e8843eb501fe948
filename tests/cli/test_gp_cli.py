"""``sinews evolve luxo|humanoid --controller gp``; ``runs show/best``, ``render`` and ``plot``."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import time
from pathlib import Path

import numpy as np
import numpy.typing as npt
import pytest
from PIL import Image

pytest.importorskip("mujoco")

from killed_runs import sinews_command, stored_generations
from sinews.cli import main
from sinews.control.gp import format_program
from sinews.experiments.gp.run import KIND as EXPERIMENT
from sinews.experiments.gp.settings import GPSettings
from sinews.experiments.kinds import best_of
from sinews.experiments.run_files import fitness_plot
from sinews.figures import luxo
from sinews.figures.tasks import standing_height
from sinews.render import FigureGeometry, FigurePainter, TaskScene
from sinews.render.view import View
from sinews.store import RunStore

TINY = ["--controller", "gp", "--population", "8", "--generations", "2", "--seconds", "0.5",
        "--seed", "1"]  # fmt: skip
POST, RED, BLUE = (150, 140, 128), (200, 40, 40), (30, 110, 200)  # the scene's marks
BACKGROUND = (250, 248, 243)
PIXELS = (320, 240)


def sinews(capsys: pytest.CaptureFixture[str], *args: str) -> tuple[int, str, str]:
    """Run the CLI; its exit status, stdout and stderr."""
    status = main(list(args))
    out, err = capsys.readouterr()
    return status, out, err


def evolve(capsys: pytest.CaptureFixture[str], db: Path, figure: str, *args: str) -> None:
    """A tiny GP run of ``figure`` (run 1 of ``db``)."""
    status, out, err = sinews(capsys, "evolve", figure, *TINY, *args, "--db", str(db))
    assert status == 0, err
    assert "generation 2/2" in err and "(list" in out


Picture = tuple[npt.NDArray[np.uint8], View, dict[str, npt.NDArray[np.float64]], TaskScene]


def picture(capsys: pytest.CaptureFixture[str], db: Path, path: Path) -> Picture:
    """``render 1 --best`` to a PNG; its pixels, camera, last frame's sites, and the scene."""
    status, _, err = sinews(capsys, "render", "1", "--best", "-o", str(path),
                            "--size", str(PIXELS[0]), "--db", str(db))  # fmt: skip
    assert status == 0, err
    with RunStore(db) as store:
        (replay,) = EXPERIMENT.replay(store, [best_of(store, 1)])
    assert replay.scene is not None
    painter = FigurePainter(FigureGeometry.of(replay.figure), replay.trajectory, size=PIXELS,
                            scene=replay.scene, still=True)  # fmt: skip
    sites = dict(zip(replay.figure.sites, painter.poses.sites[-1], strict=True))
    pixels = np.asarray(Image.open(path).convert("RGB"))
    assert pixels.shape == (PIXELS[1], PIXELS[0], 3)
    return pixels, painter.views[-1], sites, replay.scene


def shows(
    pixels: npt.NDArray[np.uint8], view: View, point: npt.ArrayLike, colour: tuple[int, ...],
    within: int,
) -> bool:  # fmt: skip
    """Whether ``colour`` is drawn within ``within`` pixels of the world ``point`` (x, z)."""
    x, y = (round(float(v)) for v in view.to_px(np.asarray(point, dtype=np.float64)))
    patch = pixels[y - within : y + within + 1, x - within : x + within + 1]
    return bool((patch == colour).all(axis=-1).any())


def test_a_hop_run_prints_saves_and_draws_its_program(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    db = tmp_path / "runs.db"
    evolve(capsys, db, "luxo", "--task", "hop", "--target", "1.5")
    status, out, _ = sinews(capsys, "runs", "show", "1", "--db", str(db))
    assert status == 0 and '"luxo-hop"' in out
    program = out[out.index("(list") :].strip()
    with RunStore(db) as store:
        settings = GPSettings.from_values(store.run(1).config)
        best = best_of(store, 1)
    assert settings.task_options == {"target": 1.5} and program == best.genome
    (parsed,) = settings.parse([program])  # with the run's terminals and functions
    assert len(parsed) == 3 and format_program(parsed, settings.pset) == program
    for name in ("p.txt", "p.json"):
        status, _, err = sinews(capsys, "runs", "best", "1", "-o", str(tmp_path / name),
                                "--db", str(db))  # fmt: skip
        assert status == 0, err
    assert (tmp_path / "p.txt").read_text() == program + "\n"
    document = json.loads((tmp_path / "p.json").read_text())
    assert document["program"] == program and document["joints"] == ["base_hinge", "elbow", "neck"]
    assert document["terminals"] == list(settings.pset.terminals) and "gx" in document["terminals"]
    pixels, view, _, scene = picture(capsys, db, tmp_path / "hop.png")
    assert scene.cross == 1.5 and not scene.posts and scene.target is None
    assert shows(pixels, view, (1.5, 0.0), RED, within=8)  # the X on the floor
    assert not shows(pixels, view, (0.75, 0.3), RED, within=8)
    learning, plot = str(tmp_path / "learning.mp4"), str(tmp_path / "fitness.png")
    status, _, err = sinews(capsys, "render", "1", "--generations", "all", "-o", learning,
                            "--size", "96", "--db", str(db))  # fmt: skip
    assert status == 0, err
    assert Path(learning).stat().st_size > 1000
    status, _, err = sinews(capsys, "plot", "1", "-o", plot, "--db", str(db))
    assert status == 0, err


def test_a_limbo_run_puts_the_bar_at_four_fifths_of_the_lamp_and_draws_it(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    db = tmp_path / "runs.db"
    evolve(capsys, db, "luxo", "--task", "limbo")
    with RunStore(db) as store:
        info = store.run(1)
    height = info.config["task_options"]["pole_height"]
    assert info.kind == "gp-luxo" and info.config["task"] == "luxo-limbo"
    assert height == round(0.8 * standing_height(luxo()), 4)
    pixels, view, _, scene = picture(capsys, db, tmp_path / "limbo.png")
    ((x, top),) = scene.posts
    assert x == info.config["task_options"]["pole_x"] and top == pytest.approx(height + 0.02)
    along = [shows(pixels, view, (x, z), POST, within=1) for z in np.linspace(0.1, 0.8, 5) * top]
    assert sum(along) >= 3  # the post (the lamp may pass in front of a part of it)
    bar = view.to_px(np.array([x, top]))
    assert tuple(pixels[round(bar[1]), round(bar[0])]) not in (POST, BACKGROUND)  # the bar
    assert scene.cross is not None and shows(pixels, view, (scene.cross, 0.0), RED, within=8)


@pytest.mark.parametrize(
    ("task", "args", "target"),
    [("nose", [], "nose"), ("reach", ["--target", "0.45,1.3"], [0.45, 1.3])],
)
def test_humanoid_runs_draw_the_target_and_the_hand(
    task: str, args: list[str], target: str | list[float], tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
) -> None:  # fmt: skip
    db = tmp_path / "runs.db"
    evolve(capsys, db, "humanoid", "--task", task, *args)
    with RunStore(db) as store:
        info = store.run(1)
    assert info.kind == "gp-humanoid" and info.config["task_options"] == {"target": target}
    pixels, view, sites, _ = picture(capsys, db, tmp_path / f"{task}.png")
    goal = sites["nose"] if target == "nose" else target
    assert shows(pixels, view, goal, RED, within=4)  # the ring's cross hairs
    assert shows(pixels, view, sites["hand_r"], BLUE, within=1)  # the hand that reaches


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["luxo", "--task", "hop", "--pole-height", "0.3"], "--pole-height is for the limbo"),
        (["luxo", "--task", "hop", "--target", "3"], "0.5 to 2 m ahead or behind, got 3.0"),
        (["luxo", "--target", "abc"], "--target for luxo-hop must be a distance in m"),
        (["luxo", "--target", "1,2"], "--target for luxo-hop must be a distance in m"),
        (["luxo", "--task", "waltz"], "no luxo task 'waltz'; choose from hop, limbo, dance"),
        (["snake"], "no controller called 'gp' for the snake; choose from springnet"),
        (["humanoid", "--task", "nose", "--target", "0.4,1.2"], "the nose task has no --target"),
        (["humanoid", "--task", "reach", "--target", "0.45"], "must be X,Z in m"),
        (["luxo", "--keep", "KEEP"], "--keep does not apply to gp runs"),
        (["luxo", "--masses", "3"], "--masses does not apply to gp runs"),
        (["luxo", "--strategy", "alton"], "gp runs breed with 'gp', not 'alton'"),
        (["luxo", "--config", "CONFIG"], "no fitness term called 'grace'"),
    ],
)
def test_bad_input_is_a_one_line_error_and_stores_nothing(
    args: list[str], message: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    (tmp_path / "keep.txt").write_text("0: 1\n")
    (tmp_path / "run.toml").write_text("weights = { grace = 1.0 }\n")
    files = {"KEEP": str(tmp_path / "keep.txt"), "CONFIG": str(tmp_path / "run.toml")}
    db = tmp_path / "runs.db"
    RunStore(db).close()
    args = [files.get(a, a) for a in args]
    status, _, err = sinews(capsys, "evolve", args[0], "--controller", "gp", *args[1:],
                            "--db", str(db))  # fmt: skip
    assert status == 2
    assert err.startswith("error: ") and message in err and err.count("\n") == 1
    with RunStore(db) as store:
        assert store.runs() == []


def test_reports_rate_every_generation_at_full_weight_and_agree_on_one_best(
    tmp_path: Path,
) -> None:
    """With style phased in, early bests score high on distance alone: the reports say so."""
    db = str(tmp_path / "r.db")
    args = ["evolve", "luxo", "--controller", "gp", "--task", "hop", "--population", "12",
            "--generations", "5", "--seconds", "1", "--seed", "2", "--db", db]  # fmt: skip
    env = {**os.environ, "COLUMNS": "200"}

    def sinews(*more: str) -> str:
        done = subprocess.run([*sinews_command(), *more], capture_output=True, text=True, env=env)
        assert done.returncode == 0, done.stderr
        return done.stdout

    shown = sinews(*args)
    assert "'full' rates each generation at full style" in " ".join(shown.split())
    full_best = float(shown.split("at full style weight")[-1].split()[0])
    listed = next(
        line for line in sinews("runs", "list", "--db", db).splitlines() if "│ 1 " in line
    )
    assert float(listed.split("│")[6]) == pytest.approx(full_best, abs=1e-3)  # the same best
    best = sinews("runs", "best", "1", "-o", str(tmp_path / "p.txt"), "--db", db)
    saved = float(best.split("fitness ")[1].split(")")[0])
    assert saved == pytest.approx(full_best, abs=1e-3)
    assert sinews("plot", "1", "-o", str(tmp_path / "f.png"), "--db", db).startswith("wrote")


def test_a_group_of_runs_and_a_run_that_stops_when_adequate(tmp_path: Path) -> None:
    db = str(tmp_path / "r.db")
    args = ["evolve", "luxo", "--controller", "gp", "--task", "hop", "--target", "0.5",
            "--population", "12", "--generations", "6", "--seconds", "1", "--seed", "3",
            "--runs", "2", "--until", "1.0", "--db", db]  # fmt: skip
    done = subprocess.run([*sinews_command(), *args], capture_output=True, text=True,
                          env={**os.environ, "COLUMNS": "80"})  # fmt: skip
    assert done.returncode == 0, done.stderr
    assert "2 runs of one setting" in done.stdout and "the group's best: run " in done.stdout
    assert "…" not in done.stdout  # the tables grow past 80 columns rather than cut a number
    with RunStore(db) as store:
        infos = store.runs()
    assert [i.seed for i in infos] == [3, 4]
    assert all(i.config["group"] == [1, 2] and i.config["until"] == 1.0 for i in infos)
    # a lamp that stays upright is within 1 m of an X 0.5 m away: adequate in generation 0
    assert all(i.status == "finished" and i.generations == 1 for i in infos)


def test_runs_that_restart_say_where_in_every_report(tmp_path: Path) -> None:
    """With --restart-after 1 these small runs stall and restart; the tables and plot say so."""
    db = str(tmp_path / "r.db")
    args = ["evolve", "luxo", "--controller", "gp", "--task", "hop", "--population", "8",
            "--generations", "6", "--seconds", "0.5", "--seed", "1", "--runs", "2",
            "--restart-after", "1", "--db", db]  # fmt: skip
    done = subprocess.run([*sinews_command(), *args], capture_output=True, text=True,
                          env={**os.environ, "COLUMNS": "200"})  # fmt: skip
    assert done.returncode == 0, done.stderr
    with RunStore(db) as store:
        restarts = {run: store.restarts(run) for run in (1, 2)}
        plot = fitness_plot(store, 1)
    assert all(restarts.values()) and all(0 not in found for found in restarts.values())
    assert "restarted at" in done.stdout  # the group's column
    said = f"restarted (bred afresh, at random) at generation {', '.join(map(str, restarts[2]))}"
    assert said in done.stdout
    assert {f"restart at {g}" for g in restarts[1]} <= set(plot.marks)


def test_ctrl_c_in_a_group_leaves_no_run_marked_running(tmp_path: Path) -> None:
    """The runs of a group that never began are stopped with the one interrupted, said so,
    and each resumes."""
    db = str(tmp_path / "r.db")
    args = ["evolve", "luxo", "--controller", "gp", "--task", "hop", "--population", "8",
            "--generations", "100000", "--seconds", "0.5", "--runs", "3", "--db", db]  # fmt: skip
    proc = subprocess.Popen([*sinews_command(), *args], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)  # fmt: skip
    while stored_generations(Path(db)) < 2 and proc.poll() is None:
        time.sleep(0.01)
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=120)
    assert proc.returncode == 130 and "Traceback" not in err
    assert "sinews runs resume 1" in err and "runs 2, 3 of the group did not start" in err
    with RunStore(db) as store:
        assert [(i.status, i.generations > 0) for i in store.runs()] == [
            ("failed", True), ("failed", False), ("failed", False)
        ]  # fmt: skip
    resumed = subprocess.run([*sinews_command(), "runs", "resume", "2", "--generations", "1",
                              "--db", db], capture_output=True, text=True)  # fmt: skip
    assert resumed.returncode == 0, resumed.stderr
    with RunStore(db) as store:
        assert store.run(2).status == "finished" and store.run(2).generations == 1


@pytest.mark.parametrize(
    ("extra", "message"),
    [
        (["--runs", "0"], "--runs"),
        (["--target", "5"], "0.5 to 2 m"),
        (["--until", "-1"], "until must be between"),
        (["--restart-after", "0"], "restart_after must be a whole number from 1 to"),
        (["--config", "half.toml"], "restart_after must be a whole number from 1 to"),
        (["--config", "bad.toml"], "unknown setting 'bogus'"),
        (["--config", "toes.toml"], "'toes' is not one of this run's style terms"),
        (["--config", "goal.toml"], "'distance' is not one of this run's style terms"),
        (["--config", "text.toml"], "constraints must be a list of term names"),
        (["--config", "late.toml"], "constraints_from must be a generation from 0 to"),
        (["--config", "loose.toml"], "constraints_from needs constraints"),
        (["--config", "vague.toml"], "restart_phase_in must be true or false"),
        (["--config", "anew.toml"], "restart_phase_in needs restart_after"),
    ],
)
def test_bad_group_and_termination_settings(tmp_path: Path, extra: list[str], message: str) -> None:
    (tmp_path / "bad.toml").write_text("population = 10\nbogus = 3\n")
    (tmp_path / "toes.toml").write_text('constraints = ["head", "toes"]\n')
    (tmp_path / "goal.toml").write_text('constraints = ["distance"]\n')
    (tmp_path / "text.toml").write_text('constraints = "head"\n')
    (tmp_path / "late.toml").write_text('constraints = ["head"]\nconstraints_from = "5"\n')
    (tmp_path / "loose.toml").write_text("constraints_from = 5\n")
    (tmp_path / "half.toml").write_text("restart_after = 2.5\n")
    (tmp_path / "vague.toml").write_text('restart_after = 3\nrestart_phase_in = "yes"\n')
    (tmp_path / "anew.toml").write_text("restart_phase_in = true\n")
    args = ["evolve", "luxo", "--controller", "gp", "--task", "hop", *extra, "--db", "r.db"]
    done = subprocess.run([*sinews_command(), *args], capture_output=True, text=True, cwd=tmp_path)
    assert done.returncode == 2 and done.stderr.count("\n") == 1 and message in done.stderr


def test_constraints_put_every_clean_program_first(tmp_path: Path) -> None:
    (tmp_path / "clean.toml").write_text('constraints = ["head", "fallen"]\n')
    db = str(tmp_path / "r.db")
    args = ["evolve", "luxo", "--controller", "gp", "--task", "hop", "--target", "1.0",
            "--population", "24", "--generations", "3", "--seconds", "1.5", "--seed", "2",
            "--config", str(tmp_path / "clean.toml"), "--db", db]  # fmt: skip
    done = subprocess.run([*sinews_command(), *args], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    with RunStore(db) as store:
        (info,) = store.runs()
        assert info.config["fitness"]["constraints"] == ["head", "fallen"]
        start = info.config["fitness"]["phase_in"]["start"]
        for generation in range(start, info.generations):
            rated = [i for i in store.individuals(1, generation) if not i.failed and i.terms]
            kept = [(i.terms or {})["head"] == 0 == (i.terms or {})["fallen"] for i in rated]
            clean = [float(i.fitness or 0) for i, k in zip(rated, kept, strict=True) if k]
            unclean = [float(i.fitness or 0) for i, k in zip(rated, kept, strict=True) if not k]
            assert clean and unclean  # both kinds, so the rule is seen at work
            assert min(clean) > max(unclean)
        assert fitness_plot(store, 1).marks["style and constraints start"] == start
