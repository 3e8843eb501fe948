"""The 3D figures: closed-loop GP rollouts against MuJoCo's own rollout of the same controls,
and offscreen frames against MuJoCo's own ``Renderer``.

Rollouts: P random GP programs drive `luxo3d-hop` and `humanoid3d-touch`
(the task's sensors, a program evaluation every 10 physics steps, failure
checks) in `sinews.figures.rollout`; the controls they produced are then
replayed open loop by `mujoco.rollout.rollout` on the same threads, so both
step exactly the same physics (the same contacts, the same falls). The two
are timed alternately and the best of each kept.

Frames: `sinews.render.mujoco_view.MujocoView` (following camera, shadows)
against `mujoco.Renderer` drawing the same scene from the same camera (in
a fresh interpreter: it picks its GL back end when MuJoCo is imported),
both 640×360 (quick: 320×180), frames per second. Skipped without an
OpenGL back end.
"""

from __future__ import annotations

import os
import subprocess
import sys
from collections.abc import Callable

import numpy as np

from sinews.benchmarks._measure import Measurement, Scale, best_time
from sinews.benchmarks._replay import closed_and_replayed
from sinews.control.gp import GPController, ramped_half_and_half
from sinews.experiments.gp.settings import GPSettings
from sinews.experiments.gp.simulate import wiring
from sinews.figures import require_mujoco
from sinews.figures.tasks import Task

__all__ = ["run"]


def _cases(
    settings: GPSettings, size: int, seconds: float
) -> tuple[Callable[[], object], Callable[[], object], int]:
    task = settings.task
    programs = ramped_half_and_half(settings.pset, np.random.default_rng(0), n_programs=size,
                                    n_trees=len(task.joints), min_depth=2, max_depth=6)  # fmt: skip
    controls = wiring(task)
    return closed_and_replayed(task.figure, lambda: GPController(programs, controls), size, seconds)


def _frames(task: Task, width: int, height: int, count: int) -> Measurement | None:
    require_mujoco()
    from sinews.render.mujoco_view import GLBackendError, MujocoView, default_camera

    model = task.figure.model()
    pose = model.qpos0.copy()
    try:
        view = MujocoView(model, width, height, camera=default_camera(model, pose))
    except GLBackendError:
        return None
    with view:
        view.frame(pose)
        ours = best_time(lambda: [view.frame(pose, dt=1 / 30) for _ in range(count)], 3)
        cam = view.camera
        camera = [*cam.lookat, cam.distance, cam.azimuth, cam.elevation]
    reference = _renderer_fps(task.figure.xml, width, height, count, camera)
    return Measurement(f"{task.figure.name} frame {width}x{height}", "frames/s",
                       count / ours, reference, "mujoco.Renderer, same scene")  # fmt: skip


_RENDERER = """
import sys, time
import mujoco
model = mujoco.MjModel.from_xml_string(sys.stdin.read())
width, height, count = (int(v) for v in sys.argv[1:4])
x, y, z, distance, azimuth, elevation = (float(v) for v in sys.argv[4:10])
data = mujoco.MjData(model)
mujoco.mj_forward(model, data)
camera = mujoco.MjvCamera()
camera.lookat[:] = (x, y, z)
camera.distance, camera.azimuth, camera.elevation = distance, azimuth, elevation
with mujoco.Renderer(model, height, width) as renderer:
    best = float("inf")
    for repeat in range(4):
        start = time.perf_counter()
        for _ in range(count):
            renderer.update_scene(data, camera)
            renderer.render()
        if repeat:
            best = min(best, time.perf_counter() - start)
print(count / best)
"""


def _renderer_fps(xml: str, width: int, height: int, count: int, camera: list[float]) -> float:
    """Frames/s of ``mujoco.Renderer`` on the model, in a fresh interpreter whose
    ``MUJOCO_GL`` is set before MuJoCo is imported (it chooses its back end then)."""
    from sinews.render.mujoco_view import gl_backend

    env = {**os.environ, "MUJOCO_GL": gl_backend()}
    done = subprocess.run(
        [sys.executable, "-c", _RENDERER, *map(str, (width, height, count, *camera))],
        input=xml, capture_output=True, text=True, env=env, check=False, timeout=600,
    )  # fmt: skip
    try:
        return float(done.stdout.strip().splitlines()[-1])
    except (IndexError, ValueError):
        return float("nan")


def run(scale: Scale = "full") -> list[Measurement]:
    """The 3D lamp and humanoid at P = 256 for 0.5 s (quick: P = 32, 0.2 s), then frames."""
    quick = scale != "full"
    size, seconds, repeats = {"full": (256, 0.5, 3), "quick": (32, 0.2, 2), "tiny": (4, 0.1, 1)}[
        scale
    ]
    results = []
    for name in ("luxo3d-hop", "humanoid3d-touch"):
        ours, reference, steps = _cases(GPSettings(name, {}), size, seconds)
        ours_time, reference_time = np.inf, np.inf
        for _ in range(repeats):
            ours_time = min(ours_time, best_time(ours, 1))
            reference_time = min(reference_time, best_time(reference, 1))
        results.append(
            Measurement(
                f"{name} GP P={size} x {steps} steps",
                "steps/s",
                size * steps / ours_time,
                size * steps / reference_time,
                "mujoco.rollout of the same controls",
            )
        )
    width, height, count = (320, 180, 5) if quick else (640, 360, 20)
    for name in ("luxo3d-hop", "humanoid3d-touch"):
        frames = _frames(GPSettings(name, {}).task, width, height, count)
        if frames is not None:
            results.append(frames)
    return results
