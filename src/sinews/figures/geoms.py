"""What a 3D figure looks like frame by frame: its shapes and their poses in the world.

A browser draws a 3D run (three.js in the figure studio) from this, not from
``qpos``: it needs no physics, only each shape's kind, size and colour and
where it is in each frame. The shapes are every geom of the model (the floor
plane included) and the world's own sites (the X on the floor, a target
ball), which are the task's marks; sites on the figure are sensors, not drawn,
as MuJoCo's renderer does not draw them either.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from sinews.figures._mujoco import require_mujoco

if TYPE_CHECKING:
    import mujoco

__all__ = ["SHAPE_KINDS", "Shapes", "shapes_of"]

SHAPE_KINDS = ("plane", "sphere", "capsule", "ellipsoid", "cylinder", "box")
"""Drawable kinds by MuJoCo's ``mjtGeom`` number (0 … 6 without height fields at 1)."""

_KIND_BY_NUMBER = {0: "plane", 2: "sphere", 3: "capsule", 4: "ellipsoid", 5: "cylinder", 6: "box"}

F32 = npt.NDArray[np.float32]


@dataclass(frozen=True)
class Shapes:
    """G shapes of a model and their poses over T frames.

    Attributes:
        kinds: (G,) names from `SHAPE_KINDS`.
        sizes: (G, 3) MuJoCo's sizes: half-extents of a box, radius and half-length
            of a capsule or cylinder, radius of a sphere, semi-axes of an ellipsoid.
        colours: (G, 4) RGBA in [0, 1] (a geom's material colour where it has one).
        positions: (T, G, 3) centres in the world, metres, z up.
        quaternions: (T, G, 4) orientations (w, x, y, z).
    """

    kinds: tuple[str, ...]
    sizes: F32
    colours: F32
    positions: F32
    quaternions: F32


def shapes_of(model: mujoco.MjModel, qpos: npt.ArrayLike) -> Shapes:
    """The drawable shapes of ``model`` posed by each frame of ``qpos``, (T, nq).

    Raises:
        ValueError: ``qpos`` is not (T, nq) with T ≥ 1 and finite.
    """
    mujoco = require_mujoco()
    frames = np.asarray(qpos, dtype=np.float64)
    if frames.ndim != 2 or frames.shape[1] != model.nq or len(frames) == 0:
        raise ValueError(f"qpos must be (T, {model.nq}) with T >= 1, got {frames.shape}")
    if not np.isfinite(frames).all():
        raise ValueError("qpos holds NaN or inf")
    geoms = [g for g in range(model.ngeom) if int(model.geom_type[g]) in _KIND_BY_NUMBER]
    sites = [
        s
        for s in range(model.nsite)
        if model.site_bodyid[s] == 0 and int(model.site_type[s]) in _KIND_BY_NUMBER
    ]
    colours = [
        model.mat_rgba[model.geom_matid[g]] if model.geom_matid[g] >= 0 else model.geom_rgba[g]
        for g in geoms
    ] + [model.site_rgba[s] for s in sites]
    kinds = tuple(_KIND_BY_NUMBER[int(model.geom_type[g])] for g in geoms) + tuple(
        _KIND_BY_NUMBER[int(model.site_type[s])] for s in sites
    )
    sizes = np.concatenate([model.geom_size[geoms], model.site_size[sites]]).astype(np.float32)
    data = mujoco.MjData(model)
    positions = np.empty((len(frames), len(kinds), 3), np.float32)
    quaternions = np.empty((len(frames), len(kinds), 4), np.float32)
    matrices = np.empty((len(kinds), 9))
    quaternion = np.empty(4)
    for t, frame in enumerate(frames):
        data.qpos[:] = frame
        mujoco.mj_kinematics(model, data)
        positions[t] = np.concatenate([data.geom_xpos[geoms], data.site_xpos[sites]])
        matrices[:] = np.concatenate([data.geom_xmat[geoms], data.site_xmat[sites]])
        for g, matrix in enumerate(matrices):
            mujoco.mju_mat2Quat(quaternion, matrix)
            quaternions[t, g] = quaternion
    return Shapes(
        kinds, sizes, np.array(colours, np.float32).reshape(-1, 4), positions, quaternions
    )
