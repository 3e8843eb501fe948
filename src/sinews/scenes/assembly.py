"""Assembling a scene's creatures and spare parts into ONE body for the engine.

A scene is one `Body` holding every creature it will ever show: the
creatures themselves, and pre-allocated spare parts (link springs, balloons,
babies, pooled kittens) that start inactive. Because everything is one body,
a hand attracted to another creature's hand is an ordinary attraction pair
and a held hand is an ordinary spring. The `Layout` remembers each part's
"on" values (in its body) and which parts start off; `sinews.scenes.world`
switches them.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt

from sinews.springmass import Body

__all__ = ["Assembly", "Layout", "Part"]

FloatArray = npt.NDArray[np.float64]
Color = tuple[int, int, int]


@dataclass(frozen=True)
class Part:
    """Where one creature sits in the merged body: contiguous node and edge ranges.

    Attributes:
        nodes: slice of its nodes.
        edges: slice of its own springs.
    """

    nodes: slice
    edges: slice


@dataclass(frozen=True, eq=False)
class Layout:
    """The merged body and how its parts start.

    Attributes:
        body: every node and spring with its "on" values (weight, strength, easing).
        node_shapes: (N,) how each node is drawn (see `sinews.trajectory.NODE_SHAPES`).
        node_active: (N,) False for spare nodes that start parked (weightless, hidden).
        edge_active: (E,) False for spare springs that start off (no strength, hidden).
    """

    body: Body
    node_shapes: tuple[str, ...]
    node_active: npt.NDArray[np.bool_]
    edge_active: npt.NDArray[np.bool_]


@dataclass
class _Nodes:
    names: list[str] = field(default_factory=list)
    rest: list[FloatArray] = field(default_factory=list)
    mass: list[FloatArray] = field(default_factory=list)
    weight: list[FloatArray] = field(default_factory=list)
    radius: list[FloatArray] = field(default_factory=list)
    home: list[FloatArray] = field(default_factory=list)
    wiggle: list[FloatArray] = field(default_factory=list)
    colors: list[npt.NDArray[np.uint8]] = field(default_factory=list)
    shapes: list[str] = field(default_factory=list)
    active: list[bool] = field(default_factory=list)


@dataclass
class _Springs:
    pairs: list[tuple[int, int]] = field(default_factory=list)
    rest_length: list[float] = field(default_factory=list)
    strength: list[float] = field(default_factory=list)
    easing: list[float] = field(default_factory=list)
    active: list[bool] = field(default_factory=list)


class Assembly:
    """Collects creatures, spare nodes, springs and attraction pairs into one `Layout`.

    Node names are prefixed by their creature's name (``"doll0.l_hand"``).
    """

    def __init__(self) -> None:
        self._nodes = _Nodes()
        self._springs = _Springs()
        self._attraction: list[tuple[int, int, float, float]] = []

    @property
    def n_nodes(self) -> int:
        """Nodes so far."""
        return len(self._nodes.names)

    @property
    def n_edges(self) -> int:
        """Springs so far."""
        return len(self._springs.pairs)

    def add_body(
        self,
        prefix: str,
        body: Body,
        *,
        shapes: tuple[str, ...] | None = None,
        active: bool = True,
    ) -> Part:
        """Add every node and spring of ``body`` (its attractions and actuators are dropped).

        Args:
            prefix: creature name, prepended to its node names.
            body: the creature; its colours (or grey) are kept.
            shapes: (n,) how each node is drawn; None for discs.
            active: False parks the whole creature until the scene reveals it.
        """
        first, first_edge = self.n_nodes, self.n_edges
        nodes = self._nodes
        nodes.names += [f"{prefix}.{name}" for name in body.names]
        for name in ("rest", "mass", "weight", "radius", "home", "wiggle"):
            getattr(nodes, name).append(np.asarray(getattr(body, name), dtype=np.float64))
        grey = np.full((body.n_nodes, 3), 150, dtype=np.uint8)
        nodes.colors.append(grey if body.colors is None else body.colors)
        nodes.shapes += list(shapes or ("disc",) * body.n_nodes)
        nodes.active += [active] * body.n_nodes
        for (i, j), length, strength, easing in zip(
            body.edges.tolist(), body.rest_length, body.strength, body.easing, strict=True
        ):
            self.add_spring(
                first + i, first + j, float(length), float(strength), float(easing), active=active
            )
        return Part(slice(first, self.n_nodes), slice(first_edge, self.n_edges))

    def add_node(
        self,
        name: str,
        position: tuple[float, float],
        *,
        mass: float,
        radius: float,
        color: Color,
        weight: float = 1.0,
        shape: str = "disc",
        active: bool = True,
    ) -> int:
        """Add one free node (e.g. a balloon) and return its index."""
        nodes = self._nodes
        nodes.names.append(name)
        nodes.rest.append(np.array([position], dtype=np.float64))
        for name_, value in (("mass", mass), ("weight", weight), ("radius", radius)):
            getattr(nodes, name_).append(np.array([value], dtype=np.float64))
        nodes.home.append(np.zeros(1))
        nodes.wiggle.append(np.zeros(1))
        nodes.colors.append(np.array([color], dtype=np.uint8))
        nodes.shapes.append(shape)
        nodes.active.append(active)
        return self.n_nodes - 1

    def add_spring(
        self,
        i: int,
        j: int,
        rest_length: float,
        strength: float,
        easing: float = 0.0,
        *,
        active: bool = True,
    ) -> int:
        """Add a spring between nodes ``i`` and ``j`` and return its index.

        ``strength`` and ``easing`` are its values when on; an inactive spring
        starts off.
        """
        springs = self._springs
        springs.pairs.append((i, j))
        springs.rest_length.append(rest_length)
        springs.strength.append(strength)
        springs.easing.append(easing)
        springs.active.append(active)
        return self.n_edges - 1

    def add_attraction(self, i: int, j: int, strength: float, reach: float) -> int:
        """Add a directed attraction pair (node ``i`` pulled toward node ``j``); returns its index.

        ``strength`` and ``reach`` are its values when on; every pair starts
        off (strength 0) and the scene switches it.
        """
        self._attraction.append((i, j, strength, reach))
        return len(self._attraction) - 1

    def build(self, drag: float) -> Layout:
        """The merged body with the "on" values, and which parts start off."""
        nodes, springs = self._nodes, self._springs
        attraction = np.array(self._attraction, dtype=np.float64).reshape(-1, 4)
        body = Body(
            names=tuple(nodes.names),
            rest=np.concatenate(nodes.rest),
            mass=np.concatenate(nodes.mass),
            weight=np.concatenate(nodes.weight),
            radius=np.concatenate(nodes.radius),
            edges=np.array(springs.pairs, dtype=np.int64).reshape(-1, 2),
            rest_length=np.array(springs.rest_length),
            strength=np.array(springs.strength),
            easing=np.array(springs.easing),
            home=np.concatenate(nodes.home),
            wiggle=np.concatenate(nodes.wiggle),
            drag=drag,
            attraction=attraction[:, :2].astype(np.int64),
            attraction_strength=attraction[:, 2],
            attraction_reach=attraction[:, 3],
            colors=np.concatenate(nodes.colors),
        )
        return Layout(
            body=body,
            node_shapes=tuple(nodes.shapes),
            node_active=np.array(nodes.active, dtype=bool),
            edge_active=np.array(springs.active, dtype=bool),
        )
