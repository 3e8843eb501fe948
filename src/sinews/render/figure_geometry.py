"""A figure's drawable geoms ("the system") and their poses in the x-z plane ("the states").

`FigureGeometry` reads the capsules, boxes, spheres, cylinders and ellipsoids
of a figure's compiled MuJoCo model; `FigureGeometry.poses` turns a
trajectory's ``qpos`` frames into each geom's centre and axes (and each
tracked site's position) by forward kinematics. Planar figures turn about y
only, so two axes describe a geom.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from sinews.figures import Figure, require_mujoco
from sinews.render.errors import RenderError

__all__ = ["BOX", "CAPSULE", "CYLINDER", "ELLIPSOID", "SPHERE", "FigureGeometry", "GeomPoses"]

FloatArray = npt.NDArray[np.float64]

SPHERE, CAPSULE, ELLIPSOID, CYLINDER, BOX = 2, 3, 4, 5, 6
"""The mjtGeom values of the shapes drawn."""


@dataclass(frozen=True, eq=False)
class GeomPoses:
    """Where every geom is in each frame, in the x-z plane (metres).

    Attributes:
        centers: (T, K, 2) geom centres.
        ax: (T, K, 2) each geom's local x axis.
        az: (T, K, 2) each geom's local z axis (a capsule's length runs along it).
        sites: (T, n_sites, 2) the figure's tracked sites (``figure.sites``).
    """

    centers: FloatArray
    ax: FloatArray
    az: FloatArray
    sites: FloatArray


@dataclass(frozen=True, eq=False)
class FigureGeometry:
    """The drawable geoms of a figure (the world's floor excluded).

    Build with `FigureGeometry.of`.

    Attributes:
        figure: the figure.
        kinds: (K,) MuJoCo geom type of each geom.
        half: (K, 3) each geom's half extent along its local x and z axes and
            its rounding radius, metres: ``|ax|·half[0] + |az|·half[1] + half[2]``
            bounds it.
        body: (K,) index of each geom's body in ``figure.body_names``.
        joint_bodies: (n_act,) index of the body each actuated joint moves.
    """

    figure: Figure
    kinds: npt.NDArray[np.int64]
    half: FloatArray
    body: npt.NDArray[np.int64]
    joint_bodies: npt.NDArray[np.int64]

    @classmethod
    def of(cls, figure: Figure) -> FigureGeometry:
        """Read the geoms of ``figure``'s compiled model."""
        model = figure.model()
        keep = [g for g in range(model.ngeom) if model.geom_bodyid[g] > 0]
        kinds = model.geom_type[keep].astype(np.int64)
        size = model.geom_size[keep]
        half = np.zeros((len(keep), 3))
        for k, (kind, s) in enumerate(zip(kinds.tolist(), size, strict=True)):
            if kind == CAPSULE:
                half[k] = (0.0, s[1], s[0])
            elif kind == SPHERE:
                half[k] = (0.0, 0.0, s[0])
            elif kind == CYLINDER:
                half[k] = (s[0], s[1], 0.0)
            elif kind in (BOX, ELLIPSOID):
                half[k] = (s[0], s[2], 0.0)
            else:
                raise RenderError(f"{figure.name}: cannot draw geom type {kind}")
        joints = [model.jnt_bodyid[model.joint(j).id] - 1 for j in figure.joints]
        return cls(
            figure=figure,
            kinds=kinds,
            half=half,
            body=model.geom_bodyid[keep].astype(np.int64) - 1,
            joint_bodies=np.array(joints, dtype=np.int64),
        )

    def poses(self, qpos: npt.ArrayLike) -> GeomPoses:
        """Forward kinematics of (T, nq) frames."""
        mujoco = require_mujoco()
        model = self.figure.model()
        frames = np.asarray(qpos, dtype=np.float64)
        if frames.ndim != 2 or frames.shape[1] != model.nq:
            raise RenderError(f"qpos must have shape (T, {model.nq}), got {frames.shape}")
        data = mujoco.MjData(model)
        keep = np.flatnonzero(model.geom_bodyid > 0)
        site_ids = [model.site(name).id for name in self.figure.sites]
        centers = np.empty((len(frames), len(keep), 2))
        axes = np.empty((len(frames), len(keep), 2, 3))
        sites = np.empty((len(frames), len(site_ids), 2))
        for t, q in enumerate(frames):
            data.qpos[:] = q
            mujoco.mj_kinematics(model, data)
            centers[t] = data.geom_xpos[keep][:, [0, 2]]
            axes[t] = data.geom_xmat[keep].reshape(-1, 3, 3)[:, [0, 2], :]
            sites[t] = data.site_xpos[site_ids][:, [0, 2]]
        return GeomPoses(centers, axes[..., 0], axes[..., 2], sites)

    def extents(self, poses: GeomPoses) -> FloatArray:
        """(T, 4) each frame's bounds (x_min, y_min, x_max, y_max) over all geoms."""
        reach = np.abs(poses.ax) * self.half[:, 0, None] + np.abs(poses.az) * self.half[:, 1, None]
        reach += self.half[:, 2, None]
        lo = (poses.centers - reach).min(axis=1)
        hi = (poses.centers + reach).max(axis=1)
        return np.concatenate([lo, hi], axis=1)
