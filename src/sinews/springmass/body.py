"""One spring-mass body: named nodes joined by springy edges (seed 000, Fig. 1–2)."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt

from sinews.errors import SinewsError
from sinews.springmass.actuators import ActuatorKind

__all__ = ["Body", "BodyError"]

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]


class BodyError(SinewsError):
    """A body whose arrays are inconsistent or out of range."""


def _float_array(value: npt.ArrayLike, shape: tuple[int, ...], name: str) -> FloatArray:
    array = np.array(value, dtype=np.float64)
    if array.shape != shape:
        raise BodyError(f"{name} must have shape {shape}, got {array.shape}")
    if not np.all(np.isfinite(array)):
        raise BodyError(f"{name} must be finite")
    return array


def _filled(value: npt.ArrayLike | None, shape: tuple[int, ...], fill: float) -> FloatArray:
    return np.full(shape, fill) if value is None else np.asarray(value, dtype=np.float64)


@dataclass(frozen=True, eq=False)
class Body:
    """A graph of point masses (nodes) and springs (edges) with its force-rule settings.

    Positions are metres with y up; the rest pose is where ``home`` pulls.

    Attributes:
        names: (N,) node names, unique.
        rest: (N, 2) rest-pose positions, also the start positions.
        mass: (N,) kilograms, > 0.
        weight: (N,) gravity multiplier; 1 falls, 0 floats, negative rises (balloons).
        radius: (N,) metres, for the floor and for drawing.
        edges: (E, 2) node indices of each spring, i != j.
        rest_length: (E,) ideal length of each spring, > 0.
        strength: (E,) spring constant, newtons per metre, >= 0.
        easing: (E,) fraction in [0, 1] of each edge's length error removed per step
            by moving its ends directly (the paper's optional step 5).
        home: (N,) strength of the pull toward the rest pose, newtons per metre.
        wiggle: (N,) amplitude of the seeded noise force, newtons.
        drag: velocity kept per step is ``1 - drag``, in [0, 1).
        attraction: (A, 2) directed pairs (i, j): node i is pulled toward node j.
        attraction_strength: (A,) newtons.
        attraction_reach: (A,) metres; beyond it a pair pulls not at all.
        colors: (N, 3) uint8 RGB for drawing.
        actuator_node: (R,) node each actuator sits on (see `sinews.springmass.actuators`).
        actuator_kind: (R,) `ActuatorKind` codes.
        actuator_channels: (R, 2) first and last drive channel each actuator reads.
        actuator_strength: (R,) newtons at drive 1, >= 0.
        actuator_custom: (R,) tuning value of each actuator's kind, in [0, 1].
        pose_basis: (N, K, 2) metres each node's home target moves per unit of each of K
            pose signals (`simulate`'s ``pose``): a whole-body move the springs follow.
    """

    names: tuple[str, ...]
    rest: FloatArray
    mass: FloatArray
    weight: FloatArray
    radius: FloatArray
    edges: IntArray
    rest_length: FloatArray
    strength: FloatArray
    easing: FloatArray
    home: FloatArray
    wiggle: FloatArray
    drag: float = 0.02
    attraction: IntArray = field(default_factory=lambda: np.zeros((0, 2), np.int64))
    attraction_strength: FloatArray = field(default_factory=lambda: np.zeros(0))
    attraction_reach: FloatArray = field(default_factory=lambda: np.zeros(0))
    colors: npt.NDArray[np.uint8] | None = None
    actuator_node: IntArray = field(default_factory=lambda: np.zeros(0, np.int64))
    actuator_kind: IntArray = field(default_factory=lambda: np.zeros(0, np.int64))
    actuator_channels: IntArray = field(default_factory=lambda: np.zeros((0, 2), np.int64))
    actuator_strength: FloatArray = field(default_factory=lambda: np.zeros(0))
    actuator_custom: FloatArray = field(default_factory=lambda: np.zeros(0))
    pose_basis: FloatArray = field(default_factory=lambda: np.zeros((0, 0, 2)))

    def __post_init__(self) -> None:
        names = tuple(str(n) for n in self.names)
        n = len(names)
        if n == 0:
            raise BodyError("a body needs at least one node")
        if len(set(names)) != n:
            raise BodyError("node names must be unique")
        set_ = object.__setattr__
        set_(self, "names", names)
        set_(self, "rest", _float_array(self.rest, (n, 2), "rest"))
        for name in ("mass", "weight", "radius", "home", "wiggle"):
            set_(self, name, _float_array(getattr(self, name), (n,), name))
        if np.any(self.mass <= 0):
            raise BodyError("mass must be > 0 for every node")
        if np.any(self.radius < 0):
            raise BodyError("radius must be >= 0")
        edges = np.array(self.edges, dtype=np.int64).reshape(-1, 2)
        _check_pairs(edges, n, "edges")
        set_(self, "edges", edges)
        n_edges = len(edges)
        for name in ("rest_length", "strength", "easing"):
            set_(self, name, _float_array(getattr(self, name), (n_edges,), name))
        if np.any(self.rest_length <= 0):
            raise BodyError("rest_length must be > 0")
        if np.any(self.strength < 0):
            raise BodyError("strength must be >= 0")
        if np.any((self.easing < 0) | (self.easing > 1)):
            raise BodyError("easing must be in [0, 1]")
        if not 0.0 <= float(self.drag) < 1.0:
            raise BodyError("drag must be in [0, 1)")
        set_(self, "drag", float(self.drag))
        pairs = np.array(self.attraction, dtype=np.int64).reshape(-1, 2)
        _check_pairs(pairs, n, "attraction")
        set_(self, "attraction", pairs)
        for name in ("attraction_strength", "attraction_reach"):
            set_(self, name, _float_array(getattr(self, name), (len(pairs),), name))
        self._check_actuators()
        basis = np.array(self.pose_basis, dtype=np.float64)
        if basis.size == 0:
            basis = np.zeros((n, 0, 2))
        if basis.ndim != 3 or basis.shape[0] != n or basis.shape[2] != 2:
            raise BodyError(f"pose_basis must have shape ({n}, K, 2), got {basis.shape}")
        if not np.all(np.isfinite(basis)):
            raise BodyError("pose_basis must be finite")
        set_(self, "pose_basis", basis)
        if self.colors is not None:
            colors = np.asarray(self.colors)
            if colors.shape != (n, 3):
                raise BodyError(f"colors must have shape {(n, 3)}, got {colors.shape}")
            set_(self, "colors", colors.astype(np.uint8))

    def _check_actuators(self) -> None:
        set_ = object.__setattr__
        nodes = np.array(self.actuator_node, dtype=np.int64).reshape(-1)
        n_act = len(nodes)
        if n_act and (nodes.min() < 0 or nodes.max() >= self.n_nodes):
            raise BodyError("actuator_node refers to nodes that do not exist")
        kinds = np.array(self.actuator_kind, dtype=np.int64).reshape(-1)
        channels = np.array(self.actuator_channels, dtype=np.int64).reshape(-1, 2)
        if kinds.shape != (n_act,) or channels.shape != (n_act, 2):
            raise BodyError("actuator arrays must have one entry per actuator")
        if n_act and (kinds.min() < 0 or kinds.max() > max(ActuatorKind)):
            raise BodyError("actuator_kind must be an ActuatorKind code")
        if np.any(channels[:, 0] < 0) or np.any(channels[:, 1] < channels[:, 0]):
            raise BodyError("actuator_channels must be ranges 0 <= first <= last")
        set_(self, "actuator_node", nodes)
        set_(self, "actuator_kind", kinds)
        set_(self, "actuator_channels", channels)
        for name in ("actuator_strength", "actuator_custom"):
            set_(self, name, _float_array(getattr(self, name), (n_act,), name))
        if np.any(self.actuator_strength < 0):
            raise BodyError("actuator_strength must be >= 0")
        if np.any((self.actuator_custom < 0) | (self.actuator_custom > 1)):
            raise BodyError("actuator_custom must be in [0, 1]")

    def without_actuators(self) -> Body:
        """The same body with every actuator and pose move removed (it hears no music)."""
        return dataclasses.replace(
            self,
            actuator_node=np.zeros(0, np.int64),
            actuator_kind=np.zeros(0, np.int64),
            actuator_channels=np.zeros((0, 2), np.int64),
            actuator_strength=np.zeros(0),
            actuator_custom=np.zeros(0),
            pose_basis=np.zeros((0, 0, 2)),
        )

    @property
    def n_actuators(self) -> int:
        """Number of actuators R."""
        return len(self.actuator_node)

    @classmethod
    def build(
        cls,
        names: tuple[str, ...] | list[str],
        rest: npt.ArrayLike,
        edges: npt.ArrayLike,
        *,
        mass: npt.ArrayLike | None = None,
        weight: npt.ArrayLike | None = None,
        radius: npt.ArrayLike | None = None,
        strength: npt.ArrayLike | None = None,
        rest_length: npt.ArrayLike | None = None,
        easing: npt.ArrayLike | None = None,
        home: npt.ArrayLike | None = None,
        wiggle: npt.ArrayLike | None = None,
        **kwargs: object,
    ) -> Body:
        """A body with defaults: unit masses, weight 1, springs 100 N/m at rest length.

        ``rest_length`` defaults to the edge lengths in the rest pose.
        """
        rest = np.asarray(rest, dtype=np.float64)
        edge_array = np.asarray(edges, dtype=np.int64).reshape(-1, 2)
        n, n_edges = len(names), len(edge_array)
        if rest_length is None and n_edges:
            _check_pairs(edge_array, n, "edges")
            delta = rest[edge_array[:, 1]] - rest[edge_array[:, 0]]
            rest_length = np.linalg.norm(delta, axis=1)
        return cls(
            names=tuple(names),
            rest=rest,
            edges=edge_array,
            mass=_filled(mass, (n,), 1.0),
            weight=_filled(weight, (n,), 1.0),
            radius=_filled(radius, (n,), 0.02),
            strength=_filled(strength, (n_edges,), 100.0),
            rest_length=_filled(rest_length, (n_edges,), 1.0),
            easing=_filled(easing, (n_edges,), 0.0),
            home=_filled(home, (n,), 0.0),
            wiggle=_filled(wiggle, (n,), 0.0),
            **kwargs,  # type: ignore[arg-type]
        )

    @property
    def n_nodes(self) -> int:
        """Number of nodes N."""
        return len(self.names)

    @property
    def n_edges(self) -> int:
        """Number of edges E."""
        return int(self.edges.shape[0])

    def index(self, name: str) -> int:
        """Index of the node called ``name``."""
        try:
            return self.names.index(name)
        except ValueError:
            raise BodyError(f"no node called {name!r}") from None


def _check_pairs(pairs: IntArray, n_nodes: int, name: str) -> None:
    if pairs.size and (pairs.min() < 0 or pairs.max() >= n_nodes):
        raise BodyError(f"{name} refer to nodes that do not exist")
    if np.any(pairs[:, 0] == pairs[:, 1]):
        raise BodyError(f"{name} must join two different nodes")
