"""`Figure`: an articulated figure (planar or 3D) as data, made from any suitable MJCF.

A figure is its MJCF text plus what a controller and a fitness term need to
know without reading XML: the actuated joints in actuator order, their neutral
angles, PD gains and ranges, the bodies that count as base/feet and as head,
the bodies and their parent links (for drawing), and the sensor columns (see
`sinews.figures.sensors`).

`Figure.from_mjcf` is the one constructor: it checks the MJCF, adds a contact
sensor per base/head body (and per optional touch body, e.g. an obstacle a
task places in the scene) and a position sensor per optional tracked site (a
hand, a nose), and reads everything else from the compiled model,
so a user's own MJCF works exactly like the built-in figures if it has

- a planar root: the first body's first three joints are slide x, slide z and
  hinge y (named as the user likes; the built-ins call them ``root_x``,
  ``root_z``, ``root_pitch``), or with ``root="free"`` a 3D figure whose
  first body's first joint is a free joint, and
- one ``<position kp=… kv=…>`` servo per actuated joint, no other actuators.

The initial state of a rollout is the model's default (``qpos0``), and the
neutral angles default to it, so a builder lays the bodies out in the pose the
figure rests in.
"""

from __future__ import annotations

import copy
import functools
import xml.etree.ElementTree as ET
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from sinews.errors import SinewsError
from sinews.figures._mujoco import require_mujoco
from sinews.figures.sensors import contact_sensor_name, sensor_columns, site_sensor_name

if TYPE_CHECKING:
    import mujoco

__all__ = ["Figure", "FigureError"]

FloatArray = npt.NDArray[np.float64]


class FigureError(SinewsError):
    """An MJCF that cannot be used as a figure, with the reason."""


@dataclass(frozen=True, eq=False)
class Figure:
    """An articulated figure: its MJCF and what is needed to drive and sense it.

    Build with `Figure.from_mjcf` (or a builder such as `sinews.figures.luxo`).

    Attributes:
        name: short name, e.g. ``"luxo"``.
        xml: the MJCF, including the contact sensors.
        joints: (n_act,) actuated joint names, in actuator (``ctrl``) order.
        neutral: (n_act,) neutral joint angles, rad: the rest pose's targets.
        kp: (n_act,) servo stiffness, N·m/rad.
        kv: (n_act,) servo damping, N·m·s/rad.
        joint_range: (n_act, 2) lowest and highest target, rad (±inf if unlimited).
        base_bodies: bodies that count as base or feet.
        head_bodies: bodies that count as head.
        body_names: (B,) every body but the world, in model order.
        edges: (E, 2) int32 parent-child links as indices into ``body_names``.
        sensor_names: (S,) names of the sensor columns.
        touch_bodies: further bodies with a contact-force column (e.g. a limbo pole).
        limb_bodies: bodies that must not rest on the floor (a lamp's arms, a
            person's legs, arms and trunk): one that touches it means the
            figure is down. Each has a contact-force column.
        sites: sites whose world x and z are sensor columns (e.g. a hand); with a
            free root their x, y, z and their place in the heading frame.
        root: ``"planar"`` (slide x, slide z, hinge y) or ``"free"`` (3D).
        heading_joint: with a free root, an actuated hinge about the root's vertical (a
            lamp's swivel) whose angle turns the heading frame: the figure heads where
            the part above it points. ``None``: the root's own heading.
    """

    name: str
    xml: str
    joints: tuple[str, ...]
    neutral: FloatArray
    kp: FloatArray
    kv: FloatArray
    joint_range: FloatArray
    base_bodies: tuple[str, ...]
    head_bodies: tuple[str, ...]
    body_names: tuple[str, ...]
    edges: npt.NDArray[np.int32]
    sensor_names: tuple[str, ...]
    touch_bodies: tuple[str, ...] = ()
    sites: tuple[str, ...] = ()
    limb_bodies: tuple[str, ...] = ()
    root: str = "planar"
    heading_joint: str | None = None

    @property
    def n_actuators(self) -> int:
        """Number of actuated joints n_act."""
        return len(self.joints)

    @property
    def n_sensors(self) -> int:
        """Number of sensor columns S."""
        return len(self.sensor_names)

    @property
    def force_axes(self) -> str:
        """Axes of each contact body's force columns: ``"xz"`` (planar) or ``"xyz"`` (free)."""
        return "xyz" if self.root == "free" else "xz"

    @property
    def tilt_column(self) -> str:
        """The column whose magnitude is how far the root leans from its rest attitude."""
        return "root_tilt" if self.root == "free" else "root_pitch"

    @property
    def contact_bodies(self) -> tuple[str, ...]:
        """Bodies with a contact-force column: base/feet, head, touch bodies, then limbs."""
        return tuple(
            dict.fromkeys(
                (*self.base_bodies, *self.head_bodies, *self.touch_bodies, *self.limb_bodies)
            )
        )

    def sensor_index(self, column: str) -> int:
        """Index of the sensor column named ``column`` (e.g. ``"root_x"``)."""
        try:
            return self.sensor_names.index(column)
        except ValueError:
            raise FigureError(f"{self.name} has no sensor column {column!r}") from None

    def model(self, timestep: float | None = None) -> mujoco.MjModel:
        """A fresh MuJoCo model of its own, optionally with another physics step (seconds): a
        copy of the figure's compiled model (copying is ~10x faster than compiling)."""
        model = copy.deepcopy(_compiled(self.xml))
        if timestep is not None:
            model.opt.timestep = timestep
        return model

    def edited(
        self,
        mjcf: ET.Element,
        *,
        sites: Sequence[str] = (),
        touch_bodies: Sequence[str] = (),
        floor_only: Sequence[str] = (),
    ) -> Figure:
        """This figure again from its edited MJCF (``ET.fromstring(self.xml)`` with a target
        or a pole added, say), sensing ``sites`` and ``touch_bodies`` besides its own; the
        same name, root, base, head and limb bodies (see `from_mjcf`)."""
        return Figure.from_mjcf(
            ET.tostring(mjcf, encoding="unicode"),
            name=self.name,
            base_bodies=self.base_bodies,
            head_bodies=self.head_bodies,
            touch_bodies=(*self.touch_bodies, *touch_bodies),
            sites=(*self.sites, *sites),
            limb_bodies=self.limb_bodies,
            root=self.root,
            floor_only=floor_only,
            heading_joint=self.heading_joint,
        )

    @classmethod
    def from_mjcf(
        cls,
        xml: str,
        *,
        name: str,
        base_bodies: Sequence[str],
        head_bodies: Sequence[str] = (),
        neutral: npt.ArrayLike | None = None,
        touch_bodies: Sequence[str] = (),
        sites: Sequence[str] = (),
        limb_bodies: Sequence[str] = (),
        root: str = "planar",
        floor_only: Sequence[str] = (),
        heading_joint: str | None = None,
    ) -> Figure:
        """Make a figure from MJCF text with a planar (or free) root and position servos.

        Args:
            xml: the MJCF document.
            name: the figure's name.
            base_bodies: names of the bodies that count as base or feet.
            head_bodies: names of the bodies that count as head.
            neutral: (n_act,) neutral angles, rad; default the joints' ``qpos0``.
            touch_bodies: further bodies whose contact force is sensed.
            sites: sites whose world position is sensed.
            limb_bodies: bodies whose floor contact means the figure is down
                (their sensors feel the floor only).
            root: ``"planar"`` or ``"free"`` (the first body's first joint is free).
            floor_only: further contact bodies whose sensors feel only the floor
                (e.g. a 3D person's head, which its own hand may touch).
            heading_joint: see the attribute (free root only).

        Returns:
            The figure, whose MJCF has a contact sensor per base/head/touch body
            and a position sensor per site added.

        Raises:
            FigureError: the MJCF does not compile or breaks one of the rules above.
        """
        contact = tuple(dict.fromkeys((*base_bodies, *head_bodies, *touch_bodies, *limb_bodies)))
        if not base_bodies:
            raise FigureError(f"{name}: name at least one base or foot body")
        model = _compile(xml)
        missing = [b for b in contact if _id(model, "body", b) < 0]
        if missing:
            raise FigureError(f"{name}: no body named {', '.join(map(repr, missing))}")
        missing = [s for s in sites if _id(model, "site", s) < 0]
        if missing:
            raise FigureError(f"{name}: no site named {', '.join(map(repr, missing))}")
        if root == "free":
            _check_free_root(model, name)
        elif root == "planar":
            _check_planar_root(model, name)
        else:
            raise FigureError(f"{name}: the root is 'planar' or 'free', not {root!r}")
        limbs_only = [
            b for b in limb_bodies if b not in (*base_bodies, *head_bodies, *touch_bodies)
        ]
        limbs_only += [b for b in floor_only if b in contact and b not in limbs_only]
        xml = _with_sensors(xml, contact, sites, on_floor=limbs_only)
        model = _compiled(xml)  # read only here
        joints, kp, kv = _servos(model, name, first_joint=1 if root == "free" else 3)
        if heading_joint is not None and (root != "free" or heading_joint not in joints):
            raise FigureError(f"{name}: the heading joint must be an actuated joint of a free root")
        qpos0 = np.array([model.qpos0[model.joint(j).qposadr[0]] for j in joints])
        rest = qpos0 if neutral is None else np.array(neutral, dtype=np.float64)
        if rest.shape != (len(joints),) or not np.isfinite(rest).all():
            raise FigureError(f"{name}: neutral must be {len(joints)} finite angles")
        bodies = tuple(model.body(i).name or f"body{i}" for i in range(1, model.nbody))
        parents = model.body_parentid[2:]
        links = [(p - 1, i + 1) for i, p in enumerate(parents) if p > 0]
        edges = np.array(links, dtype=np.int32).reshape(-1, 2)
        ranges = _ranges(model, joints)
        for array in (rest, kp, kv, ranges, edges):
            array.flags.writeable = False  # a figure is a value
        return cls(
            name=name,
            xml=xml,
            joints=joints,
            neutral=rest,
            kp=kp,
            kv=kv,
            joint_range=ranges,
            base_bodies=tuple(base_bodies),
            head_bodies=tuple(head_bodies),
            body_names=bodies,
            edges=edges,
            sensor_names=sensor_columns(joints, contact, sites, root),
            touch_bodies=tuple(touch_bodies),
            sites=tuple(sites),
            limb_bodies=tuple(limb_bodies),
            root=root,
            heading_joint=heading_joint,
        )


@functools.lru_cache(maxsize=32)
def _compiled(xml: str) -> mujoco.MjModel:
    """The model compiled from ``xml``, kept for copying: never hand it out or change it."""
    return _compile(xml)


def _compile(xml: str) -> mujoco.MjModel:
    mujoco = require_mujoco()
    try:
        return mujoco.MjModel.from_xml_string(xml)
    except ValueError as exc:
        raise FigureError(f"the MJCF does not compile: {exc}") from None


def _id(model: mujoco.MjModel, kind: str, name: str) -> int:
    mujoco = require_mujoco()
    obj = getattr(mujoco.mjtObj, f"mjOBJ_{kind.upper()}")
    return int(mujoco.mj_name2id(model, obj, name))


def _check_planar_root(model: mujoco.MjModel, name: str) -> None:
    mujoco = require_mujoco()
    slide, hinge = mujoco.mjtJoint.mjJNT_SLIDE, mujoco.mjtJoint.mjJNT_HINGE
    expected = ((slide, (1, 0, 0)), (slide, (0, 0, 1)), (hinge, (0, 1, 0)))
    ok = model.njnt >= 3 and all(
        model.jnt_bodyid[i] == 1
        and model.jnt_type[i] == kind
        and np.allclose(model.jnt_axis[i], axis)
        for i, (kind, axis) in enumerate(expected)
    )
    if not ok:
        raise FigureError(
            f"{name}: the first body's first joints must be slide x, slide z, hinge y"
        )


def _check_free_root(model: mujoco.MjModel, name: str) -> None:
    mujoco = require_mujoco()
    if not (
        model.njnt >= 1
        and model.jnt_bodyid[0] == 1
        and model.jnt_type[0] == mujoco.mjtJoint.mjJNT_FREE
        and model.body_parentid[1] == 0
    ):
        raise FigureError(f"{name}: the first body's first joint must be a free joint")
    if (model.jnt_type[1:] == mujoco.mjtJoint.mjJNT_FREE).any():
        raise FigureError(f"{name}: only the root may have a free joint")


def _with_sensors(
    xml: str, bodies: Sequence[str], sites: Sequence[str], on_floor: Sequence[str] = ()
) -> str:
    """The MJCF with a net-force contact sensor per body and a position sensor per site.

    The bodies in ``on_floor`` sense only contact with the world body (the
    floor), the others contact with anything. Sensors already there (by
    name) are kept.
    """
    root = ET.fromstring(xml)
    section = root.find("sensor")
    if section is None:
        section = ET.SubElement(root, "sensor")
    present = {el.get("name") for sensors in root.iter("sensor") for el in sensors}
    for body in bodies:
        sensor = contact_sensor_name(body)
        if sensor not in present:
            attrs = {"name": sensor, "body1": body, "data": "force", "reduce": "netforce"}
            if body in on_floor:
                attrs["body2"] = "world"
            ET.SubElement(section, "contact", attrs)
    for site in sites:
        sensor = site_sensor_name(site)
        if sensor not in present:
            ET.SubElement(section, "framepos", {"name": sensor, "objtype": "site", "objname": site})
    ET.indent(root)
    return ET.tostring(root, encoding="unicode") + "\n"


def _servos(
    model: mujoco.MjModel, name: str, first_joint: int = 3
) -> tuple[tuple[str, ...], FloatArray, FloatArray]:
    """Actuated joint names, kp and kv of the position servos, in actuator order.

    Servos may drive joints from ``first_joint`` on (the root's joints come first).
    """
    mujoco = require_mujoco()
    joints = []
    for a in range(model.nu):
        kp = model.actuator_gainprm[a, 0]
        servo = (
            model.actuator_trntype[a] == mujoco.mjtTrn.mjTRN_JOINT
            and model.actuator_gaintype[a] == mujoco.mjtGain.mjGAIN_FIXED
            and model.actuator_biastype[a] == mujoco.mjtBias.mjBIAS_AFFINE
            and kp > 0
            and model.actuator_biasprm[a, 1] == -kp
            and model.actuator_trnid[a, 0] >= first_joint
        )
        if not servo:
            label = model.actuator(a).name or f"#{a}"
            raise FigureError(f"{name}: actuator {label} is not a position servo on a joint")
        joints.append(model.joint(model.actuator_trnid[a, 0]).name)
    if not joints:
        raise FigureError(f"{name}: the MJCF has no <position> servos")
    if len(set(joints)) != len(joints) or not all(joints):
        raise FigureError(f"{name}: each servo needs its own named joint")
    kp = model.actuator_gainprm[:, 0].copy()
    kv = -model.actuator_biasprm[:, 2].copy()
    return tuple(joints), kp, kv


def _ranges(model: mujoco.MjModel, joints: Sequence[str]) -> FloatArray:
    """(n_act, 2) target range per servo: its ctrlrange, else its joint's range."""
    out = np.tile([-np.inf, np.inf], (len(joints), 1))
    for a, joint in enumerate(joints):
        j = model.joint(joint).id
        if model.actuator_ctrllimited[a]:
            out[a] = model.actuator_ctrlrange[a]
        elif model.jnt_limited[j]:
            out[a] = model.jnt_range[j]
    return out
