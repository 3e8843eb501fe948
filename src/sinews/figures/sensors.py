"""A figure's senses as named columns of one (P, S) array, filled from a batch each tick.

Columns, in order (``S = 1 + 2·(3 + n_act) + 2·n_contact + 2·n_site``):

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
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from sinews.figures.mjcf import ROOT_JOINTS

if TYPE_CHECKING:
    import mujoco

__all__ = ["SensorReader", "contact_sensor_name", "sensor_columns", "site_sensor_name"]

FloatArray = npt.NDArray[np.float64]

_ROOT_POS = ("root_x", "root_z", "root_pitch")
_ROOT_VEL = ("root_vx", "root_vz", "root_vpitch")


def contact_sensor_name(body: str) -> str:
    """Name of the MuJoCo contact sensor that measures the floor's force on ``body``."""
    return f"contact_{body}"


def site_sensor_name(site: str) -> str:
    """Name of the MuJoCo ``framepos`` sensor that measures ``site``'s position."""
    return f"site_{site}"


def sensor_columns(
    joints: Sequence[str], contact_bodies: Sequence[str], sites: Sequence[str] = ()
) -> tuple[str, ...]:
    """Names of the sensor columns for these actuated joints, contact bodies and sites."""
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
