"""A population of bodies padded into P x N arrays, the engine's settings and state."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt

from sinews.springmass.body import Body, BodyError

__all__ = ["BodyBatch", "EngineParams", "SimState", "Status"]

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]


class Status:
    """Per-body simulation status codes (`SimState.status`)."""

    OK = 0
    NON_FINITE = 1
    RUNAWAY = 2


@dataclass(frozen=True)
class EngineParams:
    """Settings shared by every body of a batch.

    Attributes:
        dt: seconds per step (the paper steps once per frame; 1/60 by default).
        gravity: metres per second squared, acting on ``weight``.
        floor: whether nodes collide with the line ``y = floor_y`` (by their radius).
        floor_y: height of the floor, metres.
        friction: fraction of horizontal velocity lost per step on the floor.
        restitution: fraction of downward speed returned as a bounce.
        home_follow: (x, y) fractions in [0, 1] of the body centroid's displacement
            that the home targets follow: (0, 0) pulls toward the fixed rest pose,
            (1, 1) keeps only the shape (the body drifts freely), (1, 0) lets a
            dancer travel sideways while home still holds it up.
        wiggle_period: seconds between the knots of the smooth wiggle noise.
        wiggle_seeded_phase: start each body's knot clock at a point of the period
            drawn from its seed, so bodies do not share one clock from t = 0 (that
            a song could line up with by chance). Off by default (scenes).
        max_speed: a node faster than this (m/s) marks its body as runaway.
    """

    dt: float = 1.0 / 60.0
    gravity: float = 9.81
    floor: bool = True
    floor_y: float = 0.0
    friction: float = 0.3
    restitution: float = 0.0
    home_follow: tuple[float, float] = (0.0, 0.0)
    wiggle_period: float = 0.4
    wiggle_seeded_phase: bool = False
    max_speed: float = 100.0

    def __post_init__(self) -> None:
        if not (np.isfinite(self.dt) and self.dt > 0):
            raise BodyError("dt must be a positive number")
        if not (np.isfinite(self.wiggle_period) and self.wiggle_period > 0):
            raise BodyError("wiggle_period must be a positive number")
        if not 0 <= self.friction <= 1 or not 0 <= self.restitution <= 1:
            raise BodyError("friction and restitution must be in [0, 1]")
        if len(self.home_follow) != 2 or not all(0 <= f <= 1 for f in self.home_follow):
            raise BodyError("home_follow must be two fractions in [0, 1]")
        if not self.max_speed > 0:
            raise BodyError("max_speed must be > 0")

    @property
    def wiggle_steps(self) -> int:
        """Steps between wiggle-noise knots (at least 1)."""
        return max(1, round(self.wiggle_period / self.dt))


@dataclass(eq=False)
class BodyBatch:
    """P bodies padded to the largest node, edge and attraction counts.

    Padding nodes and edges are inert (no mass effects, zero strength); the
    numba kernel loops only over each body's own counts, so a body's motion does
    not depend on who else is in the batch. Arrays are mutable on purpose:
    scenes switch springs and attractions on and off between steps.

    Attributes:
        n_nodes, n_edges, n_attractions: (P,) counts per body.
        rest: (P, N, 2); mass, weight, radius, home, wiggle: (P, N).
        edges: (P, E, 2); rest_length, strength, easing: (P, E).
        attraction: (P, A, 2); attraction_strength, attraction_reach: (P, A).
        n_actuators: (P,); actuator_node, actuator_kind: (P, R) int;
        actuator_channels: (P, R, 2); actuator_strength, actuator_custom: (P, R).
        pose_basis: (P, N, K, 2) home-target moves per unit pose signal.
        drag: (P,); seeds: (P,) uint64 wiggle-noise seeds.
        bodies: the bodies it was built from.
    """

    bodies: tuple[Body, ...]
    n_nodes: IntArray
    n_edges: IntArray
    n_attractions: IntArray
    rest: FloatArray
    mass: FloatArray
    weight: FloatArray
    radius: FloatArray
    home: FloatArray
    wiggle: FloatArray
    edges: IntArray
    rest_length: FloatArray
    strength: FloatArray
    easing: FloatArray
    attraction: IntArray
    attraction_strength: FloatArray
    attraction_reach: FloatArray
    n_actuators: IntArray
    actuator_node: IntArray
    actuator_kind: IntArray
    actuator_channels: IntArray
    actuator_strength: FloatArray
    actuator_custom: FloatArray
    pose_basis: FloatArray
    drag: FloatArray
    seeds: npt.NDArray[np.uint64] = field(repr=False)

    @classmethod
    def from_bodies(cls, bodies: Sequence[Body], seeds: Sequence[int] | None = None) -> BodyBatch:
        """Pad ``bodies`` into one batch; ``seeds`` (one per body) drive the wiggle noise."""
        bodies = tuple(bodies)
        if not bodies:
            raise BodyError("a batch needs at least one body")
        if seeds is None:
            seeds = [0] * len(bodies)
        if len(seeds) != len(bodies):
            raise BodyError(f"{len(seeds)} seeds for {len(bodies)} bodies")
        n_bodies = len(bodies)
        n_nodes = np.array([b.n_nodes for b in bodies], dtype=np.int64)
        n_edges = np.array([b.n_edges for b in bodies], dtype=np.int64)
        n_attr = np.array([len(b.attraction) for b in bodies], dtype=np.int64)
        n_act = np.array([b.n_actuators for b in bodies], dtype=np.int64)
        big_n = int(n_nodes.max())
        big_e, big_a, big_r = (max(1, int(n.max())) for n in (n_edges, n_attr, n_act))
        big_k = max(b.pose_basis.shape[1] for b in bodies)

        def pad(
            name: str, shape: tuple[int, ...], fill: float, dtype: type = np.float64
        ) -> npt.NDArray:
            out: npt.NDArray = np.full((n_bodies, *shape), fill, dtype=dtype)
            for p, body in enumerate(bodies):
                value = getattr(body, name)
                out[p, : len(value)] = value
            return out

        return cls(
            bodies=bodies,
            n_nodes=n_nodes,
            n_edges=n_edges,
            n_attractions=n_attr,
            rest=pad("rest", (big_n, 2), 0.0),
            mass=pad("mass", (big_n,), 1.0),
            weight=pad("weight", (big_n,), 0.0),
            radius=pad("radius", (big_n,), 0.0),
            home=pad("home", (big_n,), 0.0),
            wiggle=pad("wiggle", (big_n,), 0.0),
            edges=pad("edges", (big_e, 2), 0, np.int64),
            rest_length=pad("rest_length", (big_e,), 0.0),
            strength=pad("strength", (big_e,), 0.0),
            easing=pad("easing", (big_e,), 0.0),
            attraction=pad("attraction", (big_a, 2), 0, np.int64),
            attraction_strength=pad("attraction_strength", (big_a,), 0.0),
            attraction_reach=pad("attraction_reach", (big_a,), 0.0),
            n_actuators=n_act,
            actuator_node=pad("actuator_node", (big_r,), 0, np.int64),
            actuator_kind=pad("actuator_kind", (big_r,), 0, np.int64),
            actuator_channels=pad("actuator_channels", (big_r, 2), 0, np.int64),
            actuator_strength=pad("actuator_strength", (big_r,), 0.0),
            actuator_custom=pad("actuator_custom", (big_r,), 0.0),
            pose_basis=_pad_basis(bodies, big_n, big_k),
            drag=np.array([b.drag for b in bodies], dtype=np.float64),
            seeds=np.array([s & 0xFFFFFFFFFFFFFFFF for s in seeds], dtype=np.uint64),
        )

    @property
    def size(self) -> int:
        """Number of bodies P."""
        return len(self.bodies)

    @property
    def node_mask(self) -> npt.NDArray[np.bool_]:
        """(P, N) True where a node is real, False where it is padding."""
        return np.arange(self.rest.shape[1])[None, :] < self.n_nodes[:, None]

    def initial_state(self) -> SimState:
        """Every body at rest in its rest pose, at step 0."""
        return SimState(
            positions=self.rest.copy(),
            velocities=np.zeros_like(self.rest),
            step=0,
            status=np.zeros(self.size, dtype=np.int8),
            failed_step=np.full(self.size, -1, dtype=np.int64),
        )


def _pad_basis(bodies: tuple[Body, ...], big_n: int, big_k: int) -> FloatArray:
    out = np.zeros((len(bodies), big_n, big_k, 2))
    for p, body in enumerate(bodies):
        out[p, : body.n_nodes, : body.pose_basis.shape[1]] = body.pose_basis
    return out


@dataclass
class SimState:
    """Where a batch is: positions and velocities of every node, and per-body health.

    Attributes:
        positions: (P, N, 2) metres.
        velocities: (P, N, 2) metres per second.
        step: steps taken so far (drives the wiggle noise and external-force rows).
        status: (P,) int8 `Status` code; a failed body is frozen at its last good pose.
        failed_step: (P,) step at which each body failed, -1 if it has not.
    """

    positions: FloatArray
    velocities: FloatArray
    step: int
    status: npt.NDArray[np.int8]
    failed_step: IntArray

    def copy(self) -> SimState:
        """An independent copy."""
        return SimState(
            self.positions.copy(),
            self.velocities.copy(),
            self.step,
            self.status.copy(),
            self.failed_step.copy(),
        )

    @property
    def failed(self) -> npt.NDArray[np.bool_]:
        """(P,) True for bodies whose simulation blew up."""
        return self.status != Status.OK
