"""A figure's senses as named columns of one (P, S) array, filled from a batch each tick.

A planar figure (root slide x, slide z, hinge y) has these columns, in order
(``S = 1 + 2·(3 + n_act) + 2·n_contact + 2·n_site``):

- ``time``: seconds since the start.
- ``root_x``, ``root_z``, ``root_pitch``, then ``q_<joint>`` for each actuated
  joint: positions (m) and angles (rad).
- ``root_vx``, ``root_vz``, ``root_vpitch``, then ``dq_<joint>``: their rates.
- ``fx_<body>``, ``fz_<body>`` for each contact body (the base/feet, then the
  head, then any touch bodies such as an obstacle): the net contact force
  exerted on that body, newtons, world frame (``fz`` ≈ the weight it carries
  when standing on the floor).
- ``x_<site>``, ``z_<site>`` for each tracked site (a hand, a nose; none by
  default): its world position, m.

Positions and rates are the state after the last physics step; contact forces
come from MuJoCo ``contact`` sensors (``reduce="netforce"``) and site positions
from ``framepos`` sensors evaluated in that step, i.e. one physics step (1 ms)
behind. At time 0 the contact forces read 0 and the site positions are the
rest pose's (the rollout computes them before the first tick).

A 3D figure (a free root) has `FREE_ROOT_POS` and `FREE_ROOT_VEL` in place of
the planar root's columns, forces in x, y and z, and per site its world x, y,
z and then its position relative to the root in the root's **heading frame**
(``f_``: forward, ``l_``: left, ``u_``: up; the heading is the root body's x
axis projected on the floor, turned by the angle of a *heading joint* if the
figure has one (a lamp's swivel), so the frame turns with the figure but does
not tip with it). A goal that is a site in the world (a target) then reads as the
paper's "position relative to the goal", in the body's frame. See
`FreeSensorReader`.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from sinews.figures.mjcf import ROOT_JOINTS

if TYPE_CHECKING:
    import mujoco

__all__ = [
    "FREE_ROOT_POS",
    "FREE_ROOT_VEL",
    "FreeSensorReader",
    "SensorReader",
    "contact_sensor_name",
    "make_reader",
    "sensor_columns",
    "site_sensor_name",
]

FloatArray = npt.NDArray[np.float64]

_ROOT_POS = ("root_x", "root_z", "root_pitch")
_ROOT_VEL = ("root_vx", "root_vz", "root_vpitch")

FREE_ROOT_POS = (
    "root_x", "root_y", "root_z", "root_yaw", "root_tilt", "root_lean_f", "root_lean_l",
)  # fmt: skip
"""A free root's position columns: world x, y (m); height above the rest pose's (m); heading
(rad, about z); tilt of the root's z axis from upright (rad, ≥ 0); that axis's forward and
leftward components in the heading frame (how it leans)."""
FREE_ROOT_VEL = ("root_vx", "root_vy", "root_vz", "root_vf", "root_vl", "root_wz")
"""A free root's rate columns: world velocity (m/s); horizontal velocity forward and leftward
in the heading frame (m/s); turning rate about world z (rad/s)."""


def contact_sensor_name(body: str) -> str:
    """Name of the MuJoCo contact sensor that measures the floor's force on ``body``."""
    return f"contact_{body}"


def site_sensor_name(site: str) -> str:
    """Name of the MuJoCo ``framepos`` sensor that measures ``site``'s position."""
    return f"site_{site}"


def sensor_columns(
    joints: Sequence[str],
    contact_bodies: Sequence[str],
    sites: Sequence[str] = (),
    root: str = "planar",
) -> tuple[str, ...]:
    """Names of the sensor columns for these actuated joints, contact bodies and sites.

    ``root`` is ``"planar"`` (the default) or ``"free"`` (a 3D figure).
    """
    if root == "free":
        return (
            "time",
            *FREE_ROOT_POS,
            *(f"q_{j}" for j in joints),
            *FREE_ROOT_VEL,
            *(f"dq_{j}" for j in joints),
            *(f"f{axis}_{body}" for body in contact_bodies for axis in "xyz"),
            *(f"{axis}_{site}" for site in sites for axis in "xyz"),
            *(f"{axis}_{site}" for site in sites for axis in "flu"),
        )
    return (
        "time",
        *_ROOT_POS,
        *(f"q_{j}" for j in joints),
        *_ROOT_VEL,
        *(f"dq_{j}" for j in joints),
        *(f"f{axis}_{body}" for body in contact_bodies for axis in "xz"),
        *(f"{axis}_{site}" for site in sites for axis in "xz"),
    )


class SensorReader:
    """Fills the (P, S) sensor array from a batch's bound fields with four gathers.

    Args:
        model: the compiled figure.
        joints: the actuated joints, in actuator order.
        contact_bodies: bodies with a contact sensor (see `contact_sensor_name`).
        sites: sites with a position sensor (see `site_sensor_name`).
    """

    def __init__(
        self,
        model: mujoco.MjModel,
        joints: Sequence[str],
        contact_bodies: Sequence[str],
        sites: Sequence[str] = (),
    ) -> None:
        names = (*ROOT_JOINTS, *joints)
        self._qpos_index = np.array([model.joint(n).qposadr[0] for n in names], dtype=np.intp)
        self._qvel_index = np.array([model.joint(n).dofadr[0] for n in names], dtype=np.intp)
        adr = [model.sensor(contact_sensor_name(b)).adr[0] for b in contact_bodies]
        # netforce is (x, y, z) in the world frame, on the floor by the body: negate
        self._force_index = np.array([a + k for a in adr for k in (0, 2)], dtype=np.intp)
        adr = [model.sensor(site_sensor_name(s)).adr[0] for s in sites]
        self._site_index = np.array([a + k for a in adr for k in (0, 2)], dtype=np.intp)
        self._site_start = 1 + 2 * len(names) + len(self._force_index)
        self.n_columns = self._site_start + len(self._site_index)

    def read(
        self,
        out: FloatArray,
        time: FloatArray,
        qpos: FloatArray,
        qvel: FloatArray,
        sensordata: FloatArray,
    ) -> None:
        """Write every column of ``out`` (P, S) from the batch's (P, …) fields, in place.

        Args:
            out: (P, S) destination.
            time: (P,) simulation time.
            qpos: (P, nq) generalised positions.
            qvel: (P, nv) generalised velocities.
            sensordata: (P, nsensordata) MuJoCo sensor outputs.
        """
        n = len(self._qpos_index)
        out[:, 0] = time
        out[:, 1 : 1 + n] = qpos[:, self._qpos_index]
        out[:, 1 + n : 1 + 2 * n] = qvel[:, self._qvel_index]
        np.negative(sensordata[:, self._force_index], out=out[:, 1 + 2 * n : self._site_start])
        if len(self._site_index):
            out[:, self._site_start :] = sensordata[:, self._site_index]


class FreeSensorReader:
    """Fills the (P, S) sensor array of a figure with a free root (see the module's columns).

    Args:
        model: the compiled figure; its first joint is the free root.
        joints: the actuated joints, in actuator order.
        contact_bodies: bodies with a contact sensor (see `contact_sensor_name`).
        sites: sites with a position sensor (see `site_sensor_name`).
        heading_joint: a hinge about the root's vertical whose angle (and rate) adds to the
            root's heading (and turning rate), or ``None``.
    """

    def __init__(
        self,
        model: mujoco.MjModel,
        joints: Sequence[str],
        contact_bodies: Sequence[str],
        sites: Sequence[str] = (),
        heading_joint: str | None = None,
    ) -> None:
        self._turn: tuple[int, int] | None = None
        if heading_joint is not None:
            joint = model.joint(heading_joint)
            self._turn = (int(joint.qposadr[0]), int(joint.dofadr[0]))
        self._rest_z = float(model.qpos0[2])
        self._qpos_index = np.array([model.joint(n).qposadr[0] for n in joints], dtype=np.intp)
        self._qvel_index = np.array([model.joint(n).dofadr[0] for n in joints], dtype=np.intp)
        adr = [model.sensor(contact_sensor_name(b)).adr[0] for b in contact_bodies]
        self._force_index = np.array([a + k for a in adr for k in range(3)], dtype=np.intp)
        adr = [model.sensor(site_sensor_name(s)).adr[0] for s in sites]
        self._site_index = np.array([a + k for a in adr for k in range(3)], dtype=np.intp)
        n_act = len(joints)
        self._q = 1 + len(FREE_ROOT_POS)
        self._v = self._q + n_act
        self._dq = self._v + len(FREE_ROOT_VEL)
        self._force = self._dq + n_act
        self._site = self._force + len(self._force_index)
        self._heading = self._site + len(self._site_index)
        self.n_columns = self._heading + len(self._site_index)

    def read(
        self,
        out: FloatArray,
        time: FloatArray,
        qpos: FloatArray,
        qvel: FloatArray,
        sensordata: FloatArray,
    ) -> None:
        """Write every column of ``out`` (P, S) from the batch's (P, …) fields, in place.

        Args:
            out: (P, S) destination.
            time: (P,) simulation time.
            qpos: (P, nq) generalised positions (the free root's x, y, z, quaternion first).
            qvel: (P, nv) generalised velocities (world linear, local angular first).
            sensordata: (P, nsensordata) MuJoCo sensor outputs.
        """
        w, x, y, z = (qpos[:, 3 + k] for k in range(4))
        norm = w * w + x * x + y * y + z * z  # MuJoCo keeps it ~1; divide anyway
        norm = np.where(norm > 0.0, norm, 1.0)
        r00 = 1.0 - 2.0 * (y * y + z * z) / norm
        r10 = 2.0 * (x * y + w * z) / norm
        r20 = 2.0 * (x * z - w * y) / norm
        r21 = 2.0 * (y * z + w * x) / norm
        r02 = 2.0 * (x * z + w * y) / norm
        r12 = 2.0 * (y * z - w * x) / norm
        r22 = 1.0 - 2.0 * (x * x + y * y) / norm
        yaw = np.arctan2(r10, r00)
        if self._turn is not None:
            yaw = np.remainder(yaw + qpos[:, self._turn[0]] + np.pi, 2.0 * np.pi) - np.pi
        c, s = np.cos(yaw), np.sin(yaw)
        out[:, 0] = time
        out[:, 1] = qpos[:, 0]
        out[:, 2] = qpos[:, 1]
        out[:, 3] = qpos[:, 2] - self._rest_z
        out[:, 4] = yaw
        out[:, 5] = np.arccos(np.clip(r22, -1.0, 1.0))
        out[:, 6] = c * r02 + s * r12
        out[:, 7] = c * r12 - s * r02
        out[:, self._q : self._v] = qpos[:, self._qpos_index]
        vx, vy = qvel[:, 0], qvel[:, 1]
        v = self._v
        out[:, v] = vx
        out[:, v + 1] = vy
        out[:, v + 2] = qvel[:, 2]
        out[:, v + 3] = c * vx + s * vy
        out[:, v + 4] = c * vy - s * vx
        out[:, v + 5] = r20 * qvel[:, 3] + r21 * qvel[:, 4] + r22 * qvel[:, 5]
        if self._turn is not None:
            out[:, v + 5] += qvel[:, self._turn[1]]
        out[:, self._dq : self._force] = qvel[:, self._qvel_index]
        np.negative(sensordata[:, self._force_index], out=out[:, self._force : self._site])
        if len(self._site_index):
            world = sensordata[:, self._site_index]
            out[:, self._site : self._heading] = world
            dx = world[:, 0::3] - qpos[:, 0:1]
            dy = world[:, 1::3] - qpos[:, 1:2]
            heading = out[:, self._heading :]
            heading[:, 0::3] = c[:, None] * dx + s[:, None] * dy
            heading[:, 1::3] = c[:, None] * dy - s[:, None] * dx
            heading[:, 2::3] = world[:, 2::3] - qpos[:, 2:3]


def make_reader(
    model: mujoco.MjModel,
    joints: Sequence[str],
    contact_bodies: Sequence[str],
    sites: Sequence[str] = (),
    root: str = "planar",
    heading_joint: str | None = None,
) -> SensorReader | FreeSensorReader:
    """The reader for a figure's root: `SensorReader` (planar) or `FreeSensorReader` (free,
    with its heading joint if any)."""
    if root == "free":
        return FreeSensorReader(model, joints, contact_bodies, sites, heading_joint)
    return SensorReader(model, joints, contact_bodies, sites)
