"""Development: a `DancerGenome` grows into a tensegrity humanoid `Body`.

The main body modifiers are holistic deformations (seed 000, "Evolving Form"):
height and lankiness set limb lengths, bulkiness sets widths, sizes and
masses, torso triangularity trades shoulder width against hip width, arm
spread and stance pose the limbs. Node and edge modifiers then tune each
node's radius, density and position and each spring's ideal length, strength
and easing around what the main modifiers computed. Springs are tuned by
natural frequency (strength = reduced mass x omega²) so the body behaves alike
at any size and stays stable at the engine's 60 Hz step.
"""

from __future__ import annotations

import colorsys

import numpy as np
import numpy.typing as npt

from sinews.dancers.genome import DancerGenome
from sinews.dancers.groove import groove_basis
from sinews.dancers.responders import SPECIES, responders
from sinews.dancers.skeleton import EDGE_NAMES, EDGES, NODES, EdgeKind, edge_kind
from sinews.music.spectrum import DEFAULT_BANDS
from sinews.springmass import Body, EngineParams

__all__ = ["DANCER_ENGINE", "develop"]

DANCER_ENGINE = EngineParams(
    dt=1.0 / 60.0, home_follow=(0.97, 0.0), friction=0.35, wiggle_seeded_phase=True
)
"""Engine settings dancers are tuned for: home follows the body sideways (it can
travel) but holds it up against gravity (it stays standing)."""

_BASE_MASS = {
    "head": 5.0, "neck": 1.5, "chest": 8.0, "belly": 6.0, "pelvis": 6.0,
    "shoulder": 3.0, "elbow": 1.5, "hand": 0.6, "hip": 4.0, "knee": 3.0, "foot": 1.2,
}  # fmt: skip
_BASE_RADIUS = {
    "neck": 0.035, "chest": 0.06, "belly": 0.055, "pelvis": 0.055, "shoulder": 0.045,
    "elbow": 0.035, "hand": 0.03, "hip": 0.045, "knee": 0.04, "foot": 0.035,
}  # fmt: skip
_OMEGA = {EdgeKind.BONE: 1.0, EdgeKind.TORSO: 0.8, EdgeKind.BRACE: 0.45}
"""Relative natural frequency of each kind of spring."""

_STIFFNESS_OMEGA = (5.0, 17.0)
"""Natural frequency (rad/s) of a bone at stiffness genes 0 and 1."""
_HOME_OMEGA = (10.0, 18.0)
"""Natural frequency (rad/s) of the home pull at groundedness genes 0 and 1."""
_DRAG = (0.06, 0.15)
"""Velocity lost per frame at drag genes 0 and 1 (was 0.01–0.08: a move rang on for
beats; now it settles before the next beat)."""
_WIGGLE = (0.0, 1.5)
"""Wiggle acceleration (m/s²) at jitter genes 0 and 1."""
RESPONDER_MASS_POWER = 0.5
"""A responder's force grows as (node mass / `RESPONDER_MASS_REF` kg) to this power: a
heavy node gets more newtons but still less acceleration than a light one, so the
pelvis and chest sway and bounce visibly while a hand still flies further."""
RESPONDER_MASS_REF = 1.0
MIN_PULL = (60.0, 120.0)
"""Newtons it takes at least to stretch a spring by its own rest length, at stiffness
genes 0 and 1: strength is at least this / rest length. A given pull stretches a short
spring by a larger share of its length, so the short neck and shoulder springs of light,
soft bodies were the ones past 1.5× rest length."""


def _part(name: str) -> str:
    return name.split("_", 1)[-1]


def _lerp(lo: float, hi: float, t: float | npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
    return np.asarray(lo + (hi - lo) * t, dtype=np.float64)


def _rest_pose(g: dict[str, float]) -> dict[str, tuple[float, float]]:
    """Rest positions (metres, feet on the floor at x = 0) from the body genes."""
    height = float(_lerp(1.5, 1.9, g["height"]))
    head_r = float(_lerp(0.075, 0.13, g["head_size"]))
    leg = height * float(_lerp(0.40, 0.52, g["lankiness"]))
    upper_arm = height * float(_lerp(0.15, 0.21, g["lankiness"]))
    forearm = height * float(_lerp(0.13, 0.19, g["lankiness"]))
    width = height * float(_lerp(0.08, 0.14, g["bulkiness"]))
    tri = g["torso_triangularity"]
    shoulder_x = width * float(_lerp(0.7, 1.5, tri))
    hip_x = width * float(_lerp(1.15, 0.6, tri))
    foot_x = hip_x + height * float(_lerp(-0.02, 0.16, g["stance"]))
    foot_y = 0.035
    hip_y = foot_y + leg
    head_y = height - head_r
    neck_y = head_y - head_r - 0.03 * height
    shoulder_y = neck_y - 0.03 * height
    pelvis_y = hip_y + 0.04 * height
    angle = float(_lerp(np.radians(8), np.radians(70), g["arm_spread"]))
    fore_angle = angle * 0.55
    elbow = (shoulder_x + upper_arm * np.sin(angle), shoulder_y - upper_arm * np.cos(angle))
    hand = (elbow[0] + forearm * np.sin(fore_angle), elbow[1] - forearm * np.cos(fore_angle))
    spine = neck_y - pelvis_y
    pose = {
        "head": (0.0, head_y),
        "neck": (0.0, neck_y),
        "chest": (0.0, pelvis_y + 0.68 * spine),
        "belly": (0.0, pelvis_y + 0.34 * spine),
        "pelvis": (0.0, pelvis_y),
    }
    for sign, side in ((-1.0, "l"), (1.0, "r")):
        pose[f"{side}_shoulder"] = (sign * shoulder_x, shoulder_y)
        pose[f"{side}_elbow"] = (sign * elbow[0], elbow[1])
        pose[f"{side}_hand"] = (sign * hand[0], hand[1])
        pose[f"{side}_hip"] = (sign * hip_x, hip_y)
        pose[f"{side}_knee"] = (sign * 0.5 * (hip_x + foot_x), foot_y + 0.5 * leg)
        pose[f"{side}_foot"] = (sign * foot_x, foot_y)
    return pose


def _colors(g: dict[str, float], node_genes: npt.NDArray[np.float64]) -> npt.NDArray[np.uint8]:
    """Colourful DNA: each node's hue and lightness come from its own genes."""
    spread = 0.35 * g["colorfulness"]
    rgb = []
    for radius_gene, density_gene, dx_gene, _ in node_genes:
        hue = (g["hue"] + spread * (density_gene - 0.5) * 2 + 0.1 * (dx_gene - 0.5)) % 1.0
        light = 0.38 + 0.25 * radius_gene
        rgb.append(colorsys.hls_to_rgb(hue, light, 0.55 + 0.4 * g["colorfulness"]))
    return np.clip(np.round(np.array(rgb) * 255), 0, 255).astype(np.uint8)


def develop(
    genome: DancerGenome, *, x: float = 0.0, n_bands: int = DEFAULT_BANDS, min_pull: bool = True
) -> Body:
    """Grow the dancer's body, standing on the floor centred at ``x`` metres.

    Args:
        genome: the DNA.
        x: horizontal position of the body's centre line.
        n_bands: bands of the music analysis its responders will listen to.
        min_pull: floor every spring's strength at `MIN_PULL` / rest length (dancers);
            False keeps the springs as soft as the genes make them (the Falling for You
            ragdolls, whose arms stretch as they reach).

    Returns:
        A `Body` with the nodes of `NODES`, the springs of `EDGE_NAMES`, and
        one actuator per filled responder slot (drive channel = music band), and the
        groove's pose basis (`sinews.dancers.groove`).
    """
    g = genome.body
    pose = _rest_pose(g)
    node_genes = genome.nodes
    height = pose["head"][1]
    bulk = float(_lerp(0.7, 1.5, g["bulkiness"]))
    head_r = float(_lerp(0.075, 0.13, g["head_size"]))
    rest = np.array([pose[name] for name in NODES]) + np.array([x, 0.0])
    shift = (node_genes[:, 2:4] - 0.5) * 2.0 * 0.025 * height
    rest += shift
    feet = [NODES.index("l_foot"), NODES.index("r_foot")]
    rest[feet, 1] -= shift[feet, 1]  # feet stay on the floor
    density = _lerp(0.6, 1.6, node_genes[:, 1])
    mass = np.array([_BASE_MASS[_part(n)] for n in NODES]) * bulk * density
    radius = np.array([head_r if n == "head" else _BASE_RADIUS[_part(n)] * bulk for n in NODES])
    radius *= _lerp(0.65, 1.5, node_genes[:, 0])
    radius[feet] = np.minimum(radius[feet], rest[feet, 1])

    edges = np.array(EDGES)
    edge_genes = genome.edges
    geometric = np.linalg.norm(rest[edges[:, 1]] - rest[edges[:, 0]], axis=1)
    rest_length = geometric * _lerp(0.88, 1.12, edge_genes[:, 0])
    omega = float(_lerp(*_STIFFNESS_OMEGA, g["stiffness"]))
    kind_omega = np.array([_OMEGA[edge_kind(name)] for name in EDGE_NAMES]) * omega
    m_i, m_j = mass[edges[:, 0]], mass[edges[:, 1]]
    reduced = m_i * m_j / (m_i + m_j)
    strength = reduced * kind_omega**2 * _lerp(0.5, 1.5, edge_genes[:, 1])
    if min_pull:
        strength = np.maximum(strength, _lerp(*MIN_PULL, g["stiffness"]) / rest_length)
    easing = _lerp(0.0, 0.25, edge_genes[:, 2])

    home = mass * float(_lerp(*_HOME_OMEGA, g["groundedness"])) ** 2
    wiggle = mass * float(_lerp(*_WIGGLE, g["jitter"]))
    slots = responders(genome, n_bands)
    return Body(
        names=NODES,
        rest=rest,
        mass=mass,
        weight=np.ones(len(NODES)),
        radius=radius,
        edges=edges,
        rest_length=rest_length,
        strength=strength,
        easing=easing,
        home=home,
        wiggle=wiggle,
        drag=float(_lerp(*_DRAG, g["drag"])),
        colors=_colors(g, node_genes),
        actuator_node=np.array([r.node for r in slots], dtype=np.int64),
        actuator_kind=np.array([SPECIES[r.species] for r in slots], dtype=np.int64),
        actuator_channels=np.array([r.bands for r in slots], dtype=np.int64).reshape(-1, 2),
        actuator_strength=np.array(
            [
                r.strength * (mass[r.node] / RESPONDER_MASS_REF) ** RESPONDER_MASS_POWER
                for r in slots
            ]
        ),
        actuator_custom=np.array([r.custom for r in slots]),
        pose_basis=groove_basis(rest, g),
    )
