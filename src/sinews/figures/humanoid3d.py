"""A 3D humanoid ("Herman"): 31 degrees of freedom, every hinge under a PD servo.

The paper's humanoid "had a total of 28 degrees of freedom. Between 4 and 10
… were controlled by the genetic controllers at any one time … (the others
were under simple dynamic control)". This one has a free root (6) and 25
limited hinges, each with a PD position servo: a task's programs drive 4–10
of them and the rest hold the standing pose (`sinews.figures.tasks3d`).

Bodies and hinges (axes in the body frame; x forward, y left, z up):

- ``pelvis`` (free root ``root``);
- ``torso``: ``waist_y`` (bend forward > 0), ``waist_x`` (lean right > 0),
  ``waist_z`` (turn left > 0); ``head``: ``neck_y`` (nod > 0), ``neck_z``
  (look left > 0), with a ``nose``;
- ``upper_arm_{l,r}``: ``shoulder_x_{l,r}`` (left arm out > 0, right arm out < 0),
  ``shoulder_y_{l,r}`` (arm forward < 0), ``shoulder_z_{l,r}`` (rotation about
  the arm); ``forearm_{l,r}``: ``elbow_{l,r}`` (bend < 0), with the hand;
- ``thigh_{l,r}``: ``hip_x``, ``hip_y`` (leg forward < 0), ``hip_z``;
  ``shin_{l,r}``: ``knee`` (bend > 0); ``foot_{l,r}``: ``ankle_y``, ``ankle_x``.

Adult proportions (1.78 m, 68 kg; segment lengths and masses after the usual
anthropometric tables). The rest pose (all hinges 0) stands straight with the
arms hanging. Sites: ``hand_{l,r}`` (the fingertips), ``shoulder_{l,r}``,
``nose`` (its tip), ``head_centre``. Hands and forearms collide with the
floor, the head, the nose and the trunk (so a hand on the nose stays
outside the head); every other pair of parts passes through each other.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

from sinews.figures.figure import Figure
from sinews.figures.mjcf import Servo, fmt
from sinews.figures.mjcf3d import FREE_ROOT, TOUCHABLE, TOUCHING, document3d, hinge3d

__all__ = ["HUMANOID3D_JOINTS", "Humanoid3DShape", "JointSpec", "humanoid3d", "humanoid3d_mjcf"]

LIMBS3D = ("pelvis", "torso", "upper_arm_l", "forearm_l", "upper_arm_r", "forearm_r",
           "thigh_l", "shin_l", "thigh_r", "shin_r")  # fmt: skip
"""Everything but the feet and the head: on the floor, the person is down."""


@dataclass(frozen=True)
class JointSpec:
    """Range (rad) and servo gains of one joint kind (for ``_l``/``_r``: the left's; the
    right's ``x`` and ``z`` ranges are reflected: its arm goes out at shoulder_x < 0)."""

    lo: float
    hi: float
    kp: float
    kv: float
    torque: float


JOINTS: Mapping[str, JointSpec] = {
    "waist_y": JointSpec(-0.3, 0.7, kp=800.0, kv=50.0, torque=400.0),
    "waist_x": JointSpec(-0.4, 0.4, kp=800.0, kv=50.0, torque=400.0),
    "waist_z": JointSpec(-0.9, 0.9, kp=400.0, kv=30.0, torque=200.0),
    "neck_y": JointSpec(-0.7, 0.9, kp=60.0, kv=4.0, torque=40.0),
    "neck_z": JointSpec(-1.3, 1.3, kp=40.0, kv=3.0, torque=30.0),
    "shoulder_x": JointSpec(-0.4, 3.0, kp=200.0, kv=10.0, torque=120.0),
    "shoulder_y": JointSpec(-3.1, 1.0, kp=200.0, kv=10.0, torque=120.0),
    "shoulder_z": JointSpec(-1.5, 1.5, kp=80.0, kv=4.0, torque=60.0),
    "elbow": JointSpec(-2.6, 0.0, kp=100.0, kv=5.0, torque=60.0),
    "hip_x": JointSpec(-0.4, 0.8, kp=1000.0, kv=60.0, torque=400.0),
    "hip_y": JointSpec(-2.0, 0.6, kp=1000.0, kv=60.0, torque=400.0),
    "hip_z": JointSpec(-0.7, 0.7, kp=500.0, kv=30.0, torque=200.0),
    "knee": JointSpec(-0.05, 2.4, kp=1000.0, kv=50.0, torque=400.0),
    "ankle_y": JointSpec(-0.7, 0.9, kp=800.0, kv=40.0, torque=300.0),
    "ankle_x": JointSpec(-0.4, 0.4, kp=800.0, kv=40.0, torque=300.0),
}
"""Every joint kind: range and servo."""

_ORDER = (
    "waist_y", "waist_x", "waist_z", "neck_y", "neck_z",
    "shoulder_x_l", "shoulder_y_l", "shoulder_z_l", "elbow_l",
    "shoulder_x_r", "shoulder_y_r", "shoulder_z_r", "elbow_r",
    "hip_x_l", "hip_y_l", "hip_z_l", "knee_l", "ankle_y_l", "ankle_x_l",
    "hip_x_r", "hip_y_r", "hip_z_r", "knee_r", "ankle_y_r", "ankle_x_r",
)  # fmt: skip
HUMANOID3D_JOINTS: tuple[str, ...] = _ORDER
"""The 25 servoed hinges, in actuator order."""


@dataclass(frozen=True)
class Humanoid3DShape:
    """Dimensions (m) and masses (kg) of the 3D humanoid (defaults: an adult, 1.78 m, 68 kg).

    Attributes:
        thigh, shin, upper_arm, forearm: (length, radius, mass) of each capsule.
        torso: (length, radius, mass) of the trunk capsule, up from the waist.
        chest: (half width, radius) of the capsule across the shoulders (massless).
        pelvis: (half width, radius, mass) of the pelvis capsule across y.
        head: (radius, mass) of the head sphere; neck: its length.
        hand: (radius, mass) of the hand sphere at the end of the forearm.
        foot: (heel, toe, half width, height, mass): the sole runs from ``-heel``
            to ``toe`` under the ankle, which sits ``height`` above the floor.
        hip_width, shoulder_width: y offset of each leg and arm.
        joints: range and servo of each joint kind.
    """

    thigh: tuple[float, float, float] = (0.45, 0.065, 7.0)
    shin: tuple[float, float, float] = (0.44, 0.05, 3.2)
    upper_arm: tuple[float, float, float] = (0.29, 0.042, 1.9)
    forearm: tuple[float, float, float] = (0.25, 0.035, 1.1)
    torso: tuple[float, float, float] = (0.5, 0.12, 26.0)
    chest: tuple[float, float] = (0.12, 0.07)
    pelvis: tuple[float, float, float] = (0.09, 0.09, 9.0)
    head: tuple[float, float] = (0.1, 4.6)
    neck: float = 0.06
    hand: tuple[float, float] = (0.045, 0.45)
    foot: tuple[float, float, float, float, float] = (0.06, 0.2, 0.05, 0.08, 1.0)
    hip_width: float = 0.1
    shoulder_width: float = 0.2
    joints: Mapping[str, JointSpec] = field(default_factory=lambda: JOINTS)

    def spec(self, kind: str) -> JointSpec:
        """The range and servo of a joint kind (``"elbow"``, ``"waist_y"``, …)."""
        return self.joints[kind]


def _capsule_down(name: str, size: tuple[float, float, float], extra: str = "") -> str:
    length, radius, mass = size
    return (
        f'<geom name="{name}" type="capsule" size="{fmt(radius)}" '
        f'fromto="0 0 0 0 0 {fmt(-length)}" mass="{fmt(mass)}" {extra}/>'
    )


def _joints(shape: Humanoid3DShape, kinds: tuple[str, ...], side: str) -> str:
    """Hinges of a limb; the right side's x and z ranges are the left's, reflected."""
    axes = {"x": (1, 0, 0), "y": (0, 1, 0), "z": (0, 0, 1)}
    out = []
    for kind in kinds:
        spec = shape.spec(kind)
        axis = axes.get(kind[-1], (0, 1, 0))
        lo, hi = spec.lo, spec.hi
        if side == "_r" and kind[-1] in "xz" and kind[-2] == "_":
            lo, hi = -hi, -lo  # mirrored: the right's range is the left's, reflected
        out.append(hinge3d(kind + side, axis, lo, hi))
    return "".join(out)


def humanoid3d_mjcf(shape: Humanoid3DShape = Humanoid3DShape(), *, friction: float = 1.0) -> str:
    """MJCF of the 3D humanoid standing on the floor (contact sensors added by `humanoid3d`)."""
    heel, toe, foot_half, height, foot_mass = shape.foot
    legs, arms = [], []
    for side, sign in (("_l", 1.0), ("_r", -1.0)):
        box = fmt((heel + toe) / 2, foot_half, height / 2)
        foot = (
            f'<geom name="foot{side}" type="box" size="{box}"'
            f' pos="{fmt((toe - heel) / 2, 0, -height / 2)}" mass="{fmt(foot_mass)}"/>'
        )
        legs.append(f"""<body name="thigh{side}" pos="{fmt(0, sign * shape.hip_width, 0)}">
        {_joints(shape, ("hip_x", "hip_y", "hip_z"), side)}
        {_capsule_down(f"thigh{side}", shape.thigh)}
        <body name="shin{side}" pos="{fmt(0, 0, -shape.thigh[0])}">
          {_joints(shape, ("knee",), side)}
          {_capsule_down(f"shin{side}", shape.shin)}
          <body name="foot{side}" pos="{fmt(0, 0, -shape.shin[0])}">
            {_joints(shape, ("ankle_y", "ankle_x"), side)}
            {foot}
          </body>
        </body>
      </body>""")
        hand_radius, hand_mass = shape.hand
        reach = shape.forearm[0] + hand_radius
        arms.append(f"""<body name="upper_arm{side}"
              pos="{fmt(0, sign * shape.shoulder_width, shape.torso[0] - shape.chest[1])}">
          {_joints(shape, ("shoulder_x", "shoulder_y", "shoulder_z"), side)}
          {_capsule_down(f"upper_arm{side}", shape.upper_arm)}
          <site name="shoulder{side}" pos="0 0 0" size="0.02" rgba="0.2 0.2 0.2 0.6"/>
          <body name="forearm{side}" pos="{fmt(0, 0, -shape.upper_arm[0])}">
            {_joints(shape, ("elbow",), side)}
            {_capsule_down(f"forearm{side}", shape.forearm, TOUCHING)}
            <geom name="hand{side}" type="sphere" size="{fmt(hand_radius)}"
                  pos="{fmt(0, 0, -shape.forearm[0])}" mass="{fmt(hand_mass)}" {TOUCHING}
                  material="accent"/>
            <site name="hand{side}" pos="{fmt(0, 0, -reach)}" size="0.015" rgba="0.1 0.1 0.1 1"/>
          </body>
        </body>""")
    torso_length, torso_radius, torso_mass = shape.torso
    chest_half, chest_radius = shape.chest
    pelvis_half, pelvis_radius, pelvis_mass = shape.pelvis
    head_radius, head_mass = shape.head
    hip_height = height + shape.shin[0] + shape.thigh[0]
    chest_z = torso_length - chest_radius
    nose_at = (head_radius * 0.95, 0, head_radius)
    body = f"""<body name="pelvis" pos="0 0 {fmt(hip_height)}">
      {FREE_ROOT}
      <geom name="pelvis" type="capsule" size="{fmt(pelvis_radius)}"
            fromto="{fmt(0, -pelvis_half, 0, 0, pelvis_half, 0)}" mass="{fmt(pelvis_mass)}"/>
      <body name="torso" pos="0 0 {fmt(pelvis_radius * 0.5)}">
        {_joints(shape, ("waist_y", "waist_x", "waist_z"), "")}
        <geom name="torso" type="capsule" size="{fmt(torso_radius)}" {TOUCHABLE}
              fromto="0 0 {fmt(torso_radius)} 0 0 {fmt(torso_length - chest_radius)}"
              mass="{fmt(torso_mass)}"/>
        <geom name="chest" type="capsule" size="{fmt(chest_radius)}" {TOUCHABLE} mass="0"
              fromto="{fmt(0, -chest_half, chest_z, 0, chest_half, chest_z)}"/>
        <body name="head" pos="0 0 {fmt(torso_length + shape.neck)}">
          {_joints(shape, ("neck_y", "neck_z"), "")}
          <geom name="head" type="sphere" size="{fmt(head_radius)}" pos="0 0 {fmt(head_radius)}"
                mass="{fmt(head_mass)}" {TOUCHABLE}/>
          <geom name="nose" type="sphere" size="0.02" pos="{fmt(*nose_at)}" mass="0"
                {TOUCHABLE} material="accent"/>
          <site name="nose" pos="{fmt(nose_at[0] + 0.02, 0, nose_at[2])}" size="0.01"
                rgba="0.8 0.1 0.1 1"/>
          <site name="head_centre" pos="0 0 {fmt(head_radius)}" size="0.01" rgba="0 0 0 0"/>
        </body>
        {arms[0]}{arms[1]}
      </body>
      {legs[0]}{legs[1]}
    </body>"""
    servos = []
    for name in _ORDER:
        kind, side = (name[:-2], name[-2:]) if name[-2:] in ("_l", "_r") else (name, "")
        spec = shape.spec(kind)
        lo, hi = spec.lo, spec.hi
        if side == "_r" and kind[-1] in "xz" and kind[-2] == "_":
            lo, hi = -hi, -lo
        servos.append((Servo(name, spec.kp, spec.kv, spec.torque), lo, hi))
    return document3d("humanoid3d", body, servos, friction=friction, armature=0.01)


def humanoid3d(
    shape: Humanoid3DShape = Humanoid3DShape(), *, friction: float = 1.0, xml: str | None = None
) -> Figure:
    """The 3D humanoid as a `Figure` (free root): feet ``foot_l``, ``foot_r``; head ``head``
    (its sensor feels the floor only: a hand on the nose is not a bump); trunk, arms and
    legs are limbs. ``xml``: the humanoid's MJCF with a task's additions (default: none)."""
    return Figure.from_mjcf(
        xml if xml is not None else humanoid3d_mjcf(shape, friction=friction),
        name="humanoid3d",
        base_bodies=("foot_l", "foot_r"),
        head_bodies=("head",),
        limb_bodies=LIMBS3D,
        root="free",
        floor_only=("head",),
    )
