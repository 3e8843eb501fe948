"""Gelatinous kittens (Oh No, Kitten Avalanche!): a seeded spring-mass cat builder.

A kitten seen from the side: a big round head with two pointed ears and two
eyes, a three-node spine, four legs (knee and paw) and a four-node tail. A
seeded `numpy.random.Generator` varies its size, plumpness, head, legs,
tail and coat. Masses follow the parts (a heavy spine and head, a light tail)
and every spring is as stiff as the engine step allows for the masses at
its ends, so a light tail is stretchy and a heavy spine is not: that, not
any special case, is why the choice of node matters when a kitten is dragged.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from sinews.springmass import Body

__all__ = ["KITTEN_NODES", "KITTEN_SHAPES", "kitten"]

# name: (x, y) in body lengths (facing +x), radius in body lengths, mass in kg
# for a kitten of length 1. Drawn in this order: far legs and tail behind
# the body, the face on top.
_NODES: dict[str, tuple[float, float, float, float]] = {
    "back_paw_far": (-0.12, -0.2, 0.05, 0.07),
    "front_paw_far": (0.36, -0.2, 0.05, 0.07),
    "back_knee_far": (-0.12, -0.06, 0.055, 0.07),
    "front_knee_far": (0.34, -0.06, 0.055, 0.07),
    "tail_tip": (-0.62, 0.8, 0.05, 0.06),
    "tail_3": (-0.66, 0.62, 0.055, 0.07),
    "tail_2": (-0.58, 0.45, 0.06, 0.08),
    "tail_1": (-0.44, 0.31, 0.065, 0.09),
    "belly": (-0.04, 0.08, 0.13, 0.25),
    "chest": (0.22, 0.09, 0.12, 0.22),
    "hips": (-0.22, 0.23, 0.13, 0.25),
    "back": (0.02, 0.26, 0.13, 0.25),
    "shoulders": (0.27, 0.25, 0.13, 0.25),
    "back_knee": (-0.22, -0.06, 0.06, 0.08),
    "back_paw": (-0.22, -0.2, 0.055, 0.08),
    "front_knee": (0.26, -0.06, 0.06, 0.08),
    "front_paw": (0.26, -0.2, 0.055, 0.08),
    "far_ear": (0.45, 0.64, 0.055, 0.07),
    "near_ear": (0.67, 0.64, 0.055, 0.07),
    "head": (0.56, 0.46, 0.21, 0.35),
    "far_eye": (0.5, 0.49, 0.045, 0.06),
    "near_eye": (0.63, 0.49, 0.045, 0.06),
}
KITTEN_NODES: tuple[str, ...] = tuple(_NODES)
"""Node names of every kitten."""
KITTEN_SHAPES: tuple[str, ...] = tuple("spike" if n.endswith("ear") else "disc" for n in _NODES)
"""How each node is drawn: pointed ears, round everything else."""


def _legs(top: str, upper: str, lower: str, end: str) -> list[tuple[str, str]]:
    """Springs of a pair of legs (near and far) hanging from body nodes ``upper``, ``lower``."""
    springs = []
    for side in ("", "_far"):
        knee, paw = f"{end}_knee{side}", f"{end}_paw{side}"
        springs += [
            (upper, knee),
            (lower, knee),
            (top, knee),
            (knee, paw),
            (lower, paw),
            (upper, paw),
        ]
    return springs


# The torso is a braced strip (top: shoulders, back, hips; bottom: chest,
# belly) so every joint sits in fat triangles and nothing folds flat.
_SPRINGS: dict[str, tuple[tuple[str, str], ...]] = {
    "bone": (
        ("shoulders", "back"), ("back", "hips"), ("chest", "belly"),
        ("shoulders", "chest"), ("back", "belly"), ("hips", "belly"), ("back", "chest"),
        ("shoulders", "belly"), ("hips", "chest"),
        ("shoulders", "head"), ("chest", "head"), ("back", "head"),
        ("hips", "tail_1"), ("back", "tail_1"), ("belly", "tail_1"),
        ("tail_1", "tail_2"), ("tail_2", "tail_3"), ("tail_3", "tail_tip"),
    ),
    "brace": (
        *_legs("back", "chest", "shoulders", "front"),
        *_legs("back", "belly", "hips", "back"),
        ("front_paw", "back_paw"), ("front_paw_far", "back_paw_far"),
        ("front_paw", "front_paw_far"), ("back_paw", "back_paw_far"),
    ),
    "tail": (("hips", "tail_2"), ("tail_1", "tail_3"), ("tail_2", "tail_tip")),
    "face": (
        ("head", "far_ear"), ("head", "near_ear"), ("far_ear", "near_ear"),
        ("shoulders", "far_ear"), ("shoulders", "near_ear"),
        ("head", "far_eye"), ("head", "near_eye"), ("far_eye", "near_eye"),
        ("far_eye", "far_ear"), ("near_eye", "near_ear"),
    ),
}  # fmt: skip
_STIFFNESS = {"bone": 1.0, "brace": 0.6, "tail": 0.6, "face": 1.0}
"""Stiffness of each kind of spring, as a fraction of what its ends can take."""
_EASING = {"bone": 0.04, "brace": 0.04, "tail": 0.02, "face": 0.3}
"""Face springs hold the eyes and ears in place mostly by easing."""
_DRAG_PER_FRAME = 0.015
"""Velocity lost per 60 Hz frame: the kittens' jelly wobbles a long while."""
_STABLE = 0.35
"""Each node's springs together stay below this fraction of the 60 Hz stability limit."""

_COATS: tuple[tuple[tuple[int, int, int], tuple[int, int, int], tuple[int, int, int]], ...] = (
    ((236, 142, 64), (250, 214, 170), (40, 32, 30)),  # ginger, cream paws
    ((128, 128, 138), (226, 226, 230), (34, 40, 30)),  # grey tabby, white socks
    ((48, 44, 50), (60, 56, 62), (214, 206, 70)),  # black, yellow eyes
    ((246, 238, 226), (250, 200, 200), (70, 120, 190)),  # white, blue eyes
    ((60, 58, 64), (246, 244, 240), (150, 190, 80)),  # tuxedo, green eyes
    ((210, 170, 120), (120, 80, 50), (40, 30, 30)),  # siamese-ish, dark points
)
"""Coats: (body, paws and ear tips, eyes)."""


def _coat(names: tuple[str, ...], rng: np.random.Generator) -> npt.NDArray[np.uint8]:
    body, points, eyes = _COATS[int(rng.integers(len(_COATS)))]
    colors = np.empty((len(names), 3))
    for i, name in enumerate(names):
        if name.endswith("eye"):
            colors[i] = eyes
        elif "paw" in name or name.endswith("ear") or name == "tail_tip":
            colors[i] = points
        elif name == "chest":
            colors[i] = 0.6 * np.array(body) + 0.4 * 255  # a light bib
        else:
            colors[i] = body
    far = np.array(["far" in n for n in names])
    colors[far] *= 0.82  # the far legs are in shadow
    colors[~far] *= rng.uniform(0.94, 1.06, size=(int((~far).sum()), 1))  # stripes
    return np.clip(np.round(colors), 0, 255).astype(np.uint8)


def kitten(rng: np.random.Generator, *, length: float = 0.5, dt: float = 1.0 / 480.0) -> Body:
    """A seeded kitten standing on y = 0, centred on x = 0, facing left or right.

    Args:
        rng: chooses size, plumpness, head, legs, tail, coat and facing.
        length: typical nose-to-rump length in metres.
        dt: the engine step its springs must be stable at.

    Returns:
        A `Body` with the nodes of `KITTEN_NODES`.
    """
    size = length * rng.uniform(0.85, 1.15)
    plump = rng.uniform(0.85, 1.25)
    head = rng.uniform(0.9, 1.2)
    legs = rng.uniform(0.8, 1.2)
    tail = rng.uniform(0.8, 1.3)
    table = np.array([_NODES[n] for n in KITTEN_NODES])
    xy, radius, mass = table[:, :2].copy(), table[:, 2].copy(), table[:, 3].copy()
    is_part = {
        part: np.array([part in n for n in KITTEN_NODES]) for part in ("tail", "paw", "knee")
    }
    face = np.array([n == "head" or n.endswith(("ear", "eye")) for n in KITTEN_NODES])
    face_anchor = xy[KITTEN_NODES.index("head")] * [1.0, 0.9]
    xy[face] = face_anchor + (xy[face] - face_anchor) * head
    radius[face] *= head
    tail_root = xy[KITTEN_NODES.index("hips")]
    xy[is_part["tail"]] = tail_root + (xy[is_part["tail"]] - tail_root) * tail
    xy[is_part["paw"], 1] *= legs
    radius[~is_part["tail"]] *= plump
    mass *= plump
    xy[:, 1] += -xy[is_part["paw"], 1].min() + radius[is_part["paw"]].max()
    xy *= size
    if rng.random() < 0.5:
        xy[:, 0] *= -1.0
    radius *= size
    mass *= size / 0.5
    names = KITTEN_NODES
    pairs, kinds = [], []
    for kind, springs in _SPRINGS.items():
        pairs += [(names.index(a), names.index(b)) for a, b in springs]
        kinds += [kind] * len(springs)
    edges = np.array(pairs)
    strength, easing = _tune(edges, kinds, mass, dt)
    return Body.build(
        names,
        xy,
        edges,
        mass=mass,
        radius=radius,
        strength=strength,
        easing=easing,
        drag=1.0 - (1.0 - _DRAG_PER_FRAME) ** (dt * 60.0),
        colors=_coat(names, rng),
    )


def _tune(
    edges: npt.NDArray[np.int64], kinds: list[str], mass: npt.NDArray[np.float64], dt: float
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """(E,) strengths and easing.

    Every spring is as stiff as its kind allows within the stability budget
    of its ends: a node of mass m with d springs gives each at most
    ``_STABLE * m / d / dt²``, so light parts (tail, paws, ears) get soft
    springs and the heavy spine stiff ones.
    """
    m_i, m_j = mass[edges[:, 0]], mass[edges[:, 1]]
    degree = np.bincount(edges.ravel(), minlength=len(mass))
    share = np.minimum(m_i / degree[edges[:, 0]], m_j / degree[edges[:, 1]])
    stiffness = np.array([_STIFFNESS[k] for k in kinds])
    return stiffness * _STABLE * share / dt**2, np.array([_EASING[k] for k in kinds])
