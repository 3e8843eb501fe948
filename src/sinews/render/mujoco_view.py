"""Pictures of 3D figure runs drawn by MuJoCo's own renderer, offscreen: PNG, strobe, MP4.

MuJoCo draws with OpenGL. Without a display (a server, CI) the back end is
OSMesa, software rendering: Debian's ``libosmesa6`` (``apt-get install -y
libosmesa6``) and ``MUJOCO_GL=osmesa``; where a GPU driver exists, ``egl``.
This module picks the back end itself (``MUJOCO_GL`` if set, else ``osmesa``
on Linux without a display, else ``glfw``), so it works whatever was imported
first, and a missing back end is one line (`GLBackendError`) naming the
package to install.

The scene is the model's: the floor, the figure and a task's marks (the X on
the floor, the target ball, the limbo bar) are parts of the task's MJCF, so
what is drawn is what was simulated. `FollowCamera` follows the figure's root
smoothly and keeps a point (the target) in the frame.

Measured on 2 cores shared with other jobs (docs/figures3d.md): a 640×360
frame of the lamp 88 ms with shadows, 44 without; of the humanoid 211 and 60.
"""

from __future__ import annotations

import math
import os
import sys
import warnings
from collections.abc import Iterator, Sequence
from dataclasses import dataclass, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from sinews.figures import require_mujoco
from sinews.render._output import atomic_output, suffix_of
from sinews.render.errors import RenderError

if TYPE_CHECKING:
    import mujoco

__all__ = [
    "FollowCamera",
    "GLBackendError",
    "MujocoView",
    "gl_backend",
    "render_3d",
    "render_recordings_3d",
    "save_mp4_3d",
    "save_png_3d",
    "save_strobe_3d",
]

FloatArray = npt.NDArray[np.float64]
Image = npt.NDArray[np.uint8]

INSTALL_HINT = (
    "install Debian's libosmesa6 (apt-get install -y libosmesa6) and set MUJOCO_GL=osmesa, "
    "or MUJOCO_GL=egl where a GPU driver is installed"
)


class GLBackendError(RenderError):
    """No OpenGL back end for MuJoCo's renderer (the message names the package)."""


def gl_backend() -> str:
    """The back end to use: ``MUJOCO_GL`` if set, else ``osmesa`` on a Linux box without a
    display, else ``glfw``."""
    chosen = os.environ.get("MUJOCO_GL", "").strip().lower()
    if chosen:
        return chosen
    headless = not (os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))
    return "osmesa" if sys.platform.startswith("linux") and headless else "glfw"


def _context_class(backend: str) -> Any:
    """MuJoCo's GLContext class for ``backend``; `GLBackendError` if it cannot load."""
    platform = {"osmesa": "osmesa", "egl": "egl"}.get(backend)
    current = os.environ.get("PYOPENGL_PLATFORM")
    if platform is not None and current and current.lower() != platform:
        raise GLBackendError(
            f"MuJoCo rendering with {backend} needs PYOPENGL_PLATFORM={platform}, "
            f"not {current}; {INSTALL_HINT}"
        )
    try:
        if backend == "osmesa":
            os.environ.setdefault("PYOPENGL_PLATFORM", "osmesa")
            from mujoco.osmesa import GLContext
        elif backend == "egl":
            os.environ.setdefault("PYOPENGL_PLATFORM", "egl")
            from mujoco.egl import GLContext
        elif backend in ("glfw", "glx", "cgl", "on", "1", "true", "enable", "enabled"):
            from mujoco.glfw import GLContext
        else:
            raise GLBackendError(f"unknown MUJOCO_GL={backend!r}; {INSTALL_HINT}")
    except GLBackendError:
        raise
    except Exception as exc:  # ImportError, OSError, PyOpenGL's errors: the library is missing
        raise GLBackendError(
            f"no OpenGL back end for MuJoCo (MUJOCO_GL={backend}: {_first_line(exc)}); "
            f"{INSTALL_HINT}"
        ) from None
    return GLContext


def _first_line(exc: BaseException) -> str:
    text = str(exc).strip().splitlines()
    return f"{type(exc).__name__}: {text[0]}" if text else type(exc).__name__


@dataclass(frozen=True)
class FollowCamera:
    """A camera that follows a body and keeps a point in view.

    It looks at a point between the body (at ``height`` above the floor) and
    ``keep`` (``keep_share`` of the way), from ``distance`` m (grown with the
    gap to ``keep``), turned ``azimuth`` degrees about z and ``elevation``
    degrees (negative looks down). The look-at point follows with a lag of
    ``lag`` seconds (0: none), so hops do not shake the picture.

    Attributes:
        body: the followed body's name (default: the root body).
        distance: m.
        azimuth: degrees of the viewing direction about z: 90 looks along +y (a
            figure facing +x seen from its right), 135 from its front right.
        elevation: degrees.
        height: m above the floor of the look-at point.
        keep: a world point (x, y, z) kept in view, or None.
        keep_share: how far towards ``keep`` the camera looks, 0–1.
        lag: seconds.
    """

    body: str | None = None
    distance: float = 2.0
    azimuth: float = 135.0
    elevation: float = -20.0
    height: float = 0.3
    keep: tuple[float, float, float] | None = None
    keep_share: float = 0.4
    lag: float = 0.4


class MujocoView:
    """Offscreen MuJoCo renderer for one model: a GL context, a scene, a camera.

    Use as a context manager (or call `close`): the GL context is freed
    explicitly, not at interpreter exit.

    Args:
        model: the compiled model (a task's figure: `Figure.model()`).
        width, height: pixels.
        camera: how to follow the figure.
        shadows: draw shadows (slower in software).

    Raises:
        GLBackendError: no OpenGL back end (the message names the package).
    """

    def __init__(
        self,
        model: mujoco.MjModel,
        width: int = 640,
        height: int = 360,
        *,
        camera: FollowCamera = FollowCamera(),
        shadows: bool = True,
    ) -> None:
        mj = require_mujoco()
        if not (16 <= width <= 3840 and 16 <= height <= 2160):
            raise RenderError(f"a 3D frame is 16x16 to 3840x2160 pixels, got {width}x{height}")
        self._mj = mj
        self.model = model
        self.width, self.height = width, height
        model.vis.global_.offwidth = max(int(model.vis.global_.offwidth), width)
        model.vis.global_.offheight = max(int(model.vis.global_.offheight), height)
        context_class = _context_class(gl_backend())
        try:
            with warnings.catch_warnings():  # glfw warns of each failed step, then fails
                warnings.simplefilter("ignore")
                self._gl = context_class(width, height)
                self._gl.make_current()
                self.context = mj.MjrContext(model, mj.mjtFontScale.mjFONTSCALE_150)
        except Exception as exc:  # e.g. glfw without a display: no GL library loaded
            raise GLBackendError(
                f"cannot open an OpenGL context for MuJoCo (MUJOCO_GL={gl_backend()}: "
                f"{_first_line(exc)}); {INSTALL_HINT}"
            ) from None
        self.data = mj.MjData(model)
        self.scene = mj.MjvScene(model, maxgeom=10_000)
        mj.mjr_setBuffer(mj.mjtFramebuffer.mjFB_OFFSCREEN, self.context)
        self.option = mj.MjvOption()
        self.perturb = mj.MjvPerturb()
        self.scene.flags[mj.mjtRndFlag.mjRND_SHADOW] = shadows
        self.camera_spec = camera
        self.camera = mj.MjvCamera()
        self.camera.type = mj.mjtCamera.mjCAMERA_FREE
        self._body = 1 if camera.body is None else int(model.body(camera.body).id)
        self._lookat: FloatArray | None = None
        self._rect = mj.MjrRect(0, 0, width, height)
        self._pixels = np.empty((height, width, 3), dtype=np.uint8)

    def __enter__(self) -> MujocoView:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def close(self) -> None:
        """Free the renderer's GL resources (idempotent)."""
        gl = getattr(self, "_gl", None)
        if gl is None:
            return
        self.context.free()
        gl.free()
        self._gl = None

    def reset_camera(self) -> None:
        """Forget the camera's lagging look-at point (the next frame jumps to the figure)."""
        self._lookat = None

    def _aim(self, dt: float) -> None:
        spec = self.camera_spec
        root = self.data.xpos[self._body].copy()
        goal = np.array([root[0], root[1], spec.height])
        gap = 0.0
        if spec.keep is not None:
            keep = np.asarray(spec.keep, dtype=np.float64)
            goal += spec.keep_share * (keep - goal)
            gap = float(np.linalg.norm(keep - np.array([root[0], root[1], spec.height])))
        if self._lookat is None or spec.lag <= 0.0:
            self._lookat = goal
        else:
            alpha = 1.0 - math.exp(-max(dt, 0.0) / spec.lag)
            self._lookat = self._lookat + alpha * (goal - self._lookat)
        self.camera.lookat[:] = self._lookat
        self.camera.distance = spec.distance + 0.6 * gap
        self.camera.azimuth = spec.azimuth
        self.camera.elevation = spec.elevation

    def frame(self, qpos: npt.ArrayLike, *, dt: float = 0.0, ghosts: Sequence[Any] = ()) -> Image:
        """Draw the model at ``qpos``; ``dt`` seconds since the last frame (camera lag).

        ``ghosts``: further qpos vectors drawn in the same picture (a strobe),
        faded. Returns a new (H, W, 3) uint8 image.
        """
        mj = self._mj
        if self._gl is None:
            raise RenderError("this view is closed")
        self._gl.make_current()
        catmask = mj.mjtCatBit.mjCAT_ALL
        for k, pose in enumerate(ghosts):
            self.data.qpos[:] = pose
            mj.mj_kinematics(self.model, self.data)
            if k == 0:
                mj.mjv_updateScene(self.model, self.data, self.option, self.perturb, self.camera,
                                   catmask, self.scene)  # fmt: skip
                start = self.scene.ngeom
                _fade(self.scene, 0, start, 0.35)
            else:
                start = self.scene.ngeom
                mj.mjv_addGeoms(self.model, self.data, self.option, self.perturb,
                                mj.mjtCatBit.mjCAT_DYNAMIC, self.scene)  # fmt: skip
                _fade(self.scene, start, self.scene.ngeom, 0.35 + 0.5 * k / len(ghosts))
        self.data.qpos[:] = qpos
        mj.mj_forward(self.model, self.data)
        self._aim(dt)
        if ghosts:
            start = self.scene.ngeom
            mj.mjv_addGeoms(self.model, self.data, self.option, self.perturb,
                            mj.mjtCatBit.mjCAT_DYNAMIC, self.scene)  # fmt: skip
            mj.mjv_updateCamera(self.model, self.data, self.camera, self.scene)
        else:
            mj.mjv_updateScene(self.model, self.data, self.option, self.perturb, self.camera,
                               catmask, self.scene)  # fmt: skip
        mj.mjr_render(self._rect, self.scene, self.context)
        mj.mjr_readPixels(self._pixels, None, self._rect, self.context)
        return np.flipud(self._pixels).copy()

    def frames(self, qpos: npt.ArrayLike, fps: float) -> Iterator[Image]:
        """Every frame of a (T, nq) recording at ``fps``, the camera following."""
        frames = np.asarray(qpos, dtype=np.float64)
        self.reset_camera()
        for k, pose in enumerate(frames):
            yield self.frame(pose, dt=0.0 if k == 0 else 1.0 / fps)


def _fade(scene: Any, start: int, stop: int, alpha: float) -> None:
    """Make geoms ``start``…``stop`` of the scene see-through (a strobe's earlier poses);
    the static world (floor, marks) is left alone."""
    for i in range(start, stop):
        geom = scene.geoms[i]
        if geom.category == 2:  # mjCAT_DYNAMIC: the figure's moving parts
            geom.rgba[3] = alpha


def default_camera(model: mujoco.MjModel, qpos: npt.ArrayLike) -> FollowCamera:
    """A camera for a figure: its size sets distance and height; a site named ``target``
    is kept in view."""
    mj = require_mujoco()
    data = mj.MjData(model)
    data.qpos[:] = np.asarray(qpos, dtype=np.float64)
    mj.mj_kinematics(model, data)
    dynamic = model.body_rootid[model.geom_bodyid] == 1
    tops = data.geom_xpos[dynamic, 2] + model.geom_rbound[dynamic]
    tall = float(max(tops.max(initial=0.3), 0.3))
    keep = None
    target = int(mj.mj_name2id(model, mj.mjtObj.mjOBJ_SITE, "target"))
    if target >= 0:
        x, y, z = (float(v) for v in data.site_xpos[target])
        keep = (x, y, z)
    return FollowCamera(distance=1.5 * tall + 1.0, height=0.5 * tall, keep=keep)


def _at_middle(camera: FollowCamera, points: FloatArray) -> FollowCamera:
    """``camera`` looking at the middle of the (N, 2) floor points."""
    middle = (points.min(axis=0) + points.max(axis=0)) / 2
    return replace(camera, keep=(float(middle[0]), float(middle[1]), camera.height),
                   keep_share=1.0)  # fmt: skip


def _across(camera: FollowCamera, path_xy: FloatArray) -> FollowCamera:
    """``camera`` looking at the middle of the (T, 2) path and its kept point, from the right
    of the travel if that is over 0.3 m."""
    points = path_xy if camera.keep is None else np.vstack([path_xy, camera.keep[:2]])
    chosen = _at_middle(camera, points)
    dx, dy = path_xy[-1] - path_xy[0]
    if math.hypot(dx, dy) < 0.3:
        return chosen
    return replace(chosen, azimuth=math.degrees(math.atan2(dy, dx)) + 90.0)


def _views(model: mujoco.MjModel, qpos: FloatArray, size: tuple[int, int],
           camera: FollowCamera | None, shadows: bool = True) -> MujocoView:  # fmt: skip
    chosen = camera if camera is not None else default_camera(model, qpos[0])
    return MujocoView(model, size[0], size[1], camera=chosen, shadows=shadows)


def save_png_3d(
    model: mujoco.MjModel,
    qpos: npt.ArrayLike,
    path: str | os.PathLike[str],
    *,
    frame: int = -1,
    size: tuple[int, int] = (640, 360),
    camera: FollowCamera | None = None,
    shadows: bool = True,
) -> Path:
    """One frame (default the last) of a (T, nq) recording as a PNG."""
    from PIL import Image as PILImage

    suffix_of(path, (".png",))
    frames = _recording(model, qpos)
    with _views(model, frames, size, camera, shadows) as view:
        image = view.frame(frames[frame])
    with atomic_output(path) as tmp:
        PILImage.fromarray(image).save(tmp, format="PNG")
    return Path(path)


def save_strobe_3d(
    model: mujoco.MjModel,
    qpos: npt.ArrayLike,
    path: str | os.PathLike[str],
    *,
    count: int = 8,
    size: tuple[int, int] = (960, 540),
    camera: FollowCamera | None = None,
    shadows: bool = True,
) -> Path:
    """``count`` poses spread over a recording in one PNG, earlier ones faded; the camera
    frames the whole path. The default camera looks at the middle of the path and the
    target, from the right of the travel (first pose to last) once it is over 0.3 m, so
    the poses stand side by side whichever way the figure went."""
    from PIL import Image as PILImage

    suffix_of(path, (".png",))
    frames = _recording(model, qpos)
    if not 2 <= count <= 64:
        raise RenderError(f"a strobe shows 2 to 64 poses, got {count}")
    picks = np.unique(np.linspace(0, len(frames) - 1, count).round().astype(int))
    path_xy = frames[:, :2]
    span = float(np.ptp(path_xy, axis=0).max())
    if camera is None:
        chosen = _across(default_camera(model, frames[0]), path_xy)
    else:
        chosen = camera if camera.keep is not None else _at_middle(camera, path_xy)
    chosen = replace(chosen, lag=0.0, distance=chosen.distance + 0.8 * span)
    with MujocoView(model, size[0], size[1], camera=chosen, shadows=shadows) as view:
        # the camera looks at the middle of the path: aim from the first pose
        image = view.frame(frames[picks[-1]], ghosts=[frames[k] for k in picks[:-1]])
    with atomic_output(path) as tmp:
        PILImage.fromarray(image).save(tmp, format="PNG")
    return Path(path)


def save_mp4_3d(
    model: mujoco.MjModel,
    qpos: npt.ArrayLike,
    path: str | os.PathLike[str],
    *,
    fps: float,
    size: tuple[int, int] = (640, 360),
    camera: FollowCamera | None = None,
    shadows: bool = True,
) -> Path:
    """A (T, nq) recording at ``fps`` frames per second as an H.264 MP4, the camera following.

    Shadows cost most of a software-rendered frame (640×360, 2 busy cores: the
    humanoid 211 ms with, 60 ms without; the lamp 88 and 44).
    """
    from sinews.render.mp4 import encode_mp4

    suffix_of(path, (".mp4",))
    if size[0] % 2 or size[1] % 2:
        raise RenderError(f"H.264 needs even dimensions, got {size[0]}x{size[1]}")
    frames = _recording(model, qpos)
    with _views(model, frames, size, camera, shadows) as view, atomic_output(path) as tmp:
        encode_mp4(view.frames(frames, fps), tmp, size=size, fps=fps)
    return Path(path)


def render_3d(
    model: mujoco.MjModel,
    qpos: npt.ArrayLike,
    path: str | os.PathLike[str],
    *,
    fps: float = 30.0,
    strobe: bool = False,
    **options: Any,
) -> Path:
    """Write a recording to ``path`` by its suffix: ``.mp4`` (video), ``.png`` (the last
    frame, or with ``strobe`` a strobe)."""
    suffix = suffix_of(path, (".png", ".mp4"))
    if suffix == ".mp4":
        return save_mp4_3d(model, qpos, path, fps=fps, **options)
    if strobe:
        return save_strobe_3d(model, qpos, path, **options)
    return save_png_3d(model, qpos, path, **options)


def render_recordings_3d(
    model: mujoco.MjModel,
    recordings: Sequence[npt.ArrayLike],
    path: str | os.PathLike[str],
    *,
    fps: float,
    width: int = 640,
    shadows: bool | None = None,
    audio: str | os.PathLike[str] | None = None,
) -> Path:
    """Stored runs' replays: ``.mp4`` plays the recordings one after another (e.g. each
    generation's best: the camera starts afresh on each), with ``audio`` (a dance's song,
    from its start) if given; ``.png`` is a strobe of one. Shadows (None: on for one
    recording, off for several, where they would triple the time of a learning video).

    Args:
        model: the task's model (its figure with the scene).
        recordings: (T, nq) qpos frames, one per replayed individual.
        path: ``.mp4`` or ``.png``.
        fps: frame rate of the recordings.
        width: pixels (height: 9/16 of it, rounded to even).
    """
    size = (width - width % 2, round(width * 9 / 32) * 2)
    suffix = suffix_of(path, (".png", ".mp4"))
    frames = [_recording(model, q) for q in recordings]
    if not frames:
        raise RenderError("nothing to render")
    if suffix == ".png":
        if len(frames) != 1:
            raise RenderError("a .png strobe shows one individual; use .mp4 for several")
        return save_strobe_3d(model, frames[0], path, size=size, shadows=shadows is not False)
    from sinews.render.mp4 import encode_mp4

    camera = default_camera(model, frames[0][0])

    def every_frame(view: MujocoView) -> Iterator[Image]:
        for recording in frames:
            yield from view.frames(recording, fps)

    shade = len(frames) == 1 if shadows is None else shadows
    with MujocoView(model, *size, camera=camera, shadows=shade) as view, atomic_output(path) as tmp:
        sound = None if audio is None else Path(audio)
        encode_mp4(every_frame(view), tmp, size=size, fps=fps, audio=sound)
    return Path(path)


def _recording(model: mujoco.MjModel, qpos: npt.ArrayLike) -> FloatArray:
    frames = np.asarray(qpos, dtype=np.float64)
    if frames.ndim == 1:
        frames = frames[None]
    if frames.ndim != 2 or frames.shape[1] != model.nq or len(frames) == 0:
        raise RenderError(f"a recording is (T, {model.nq}) qpos frames, got {frames.shape}")
    if not np.isfinite(frames).all():
        raise RenderError("the recording holds NaN or inf")
    return frames
