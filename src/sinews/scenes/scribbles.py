"""Scribbles (seed 000, "Prior Work", 2004): drawings that twitch, crawl and coil.

The player draws a curve; it becomes a chain of nodes joined by stiff bones
(`sinews.scenes.scribble.resample`), and the scene's own seeded rule adds
tendons between non-adjacent nodes that contract and release over time
(`Tendons`), their rest lengths rewritten in the body every frame. The page
has no gravity but grips like a worm's bristles: a node slides easily toward
its scribble's head (the first point drawn, the big dot), hardly backward,
so every rhythm of contraction and release crawls head first and a lopsided
one goes round in circles; each keeps the character of its tendons. Several
live at once; one that crawls far off the page is put away.

Every scribble slot is pre-allocated in the scene's one body: its nodes, its
bones, and a spring for every pair of non-adjacent nodes, of which the rule
switches on only its tendons.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from sinews.scenes.assembly import Assembly
from sinews.scenes.grab import Pull
from sinews.scenes.messages import SceneEvent, SceneInput
from sinews.scenes.scene import Scene
from sinews.scenes.scribble import Tendons, resample
from sinews.scenes.world import World
from sinews.springmass import EngineParams

__all__ = ["SCRIBBLE_ENGINE", "Scribbles"]

SCRIBBLE_ENGINE = EngineParams(gravity=0.0, floor=False)
"""No gravity, no floor: scribbles lie on the page (seen from above)."""
_GRIP = (0.03, 0.8, 0.3)
"""Newton-seconds per metre against a node sliding toward its scribble's head,
away from it, and sideways."""
_MASS = 0.05
"""Kilograms per node."""
_BONE = (_MASS * 30.0**2, 0.3)
"""Bone strength (N/m, natural frequency 30 rad/s per node) and easing: bones keep their length."""
_TENDON = _MASS * 20.0**2
"""Tendon strength, N/m."""
_INKS = ((38, 70, 170), (206, 58, 62), (28, 134, 88), (146, 72, 176), (230, 136, 28))
_GROUND = 0.3
_PARK = np.array([0.0, 2000.0])


@dataclass
class _Scribble:
    slot: int
    nodes: npt.NDArray[np.int64]  # (n,) its nodes
    bones: npt.NDArray[np.int64]  # (n - 1,) its bone springs
    tendons: Tendons
    springs: npt.NDArray[np.int64]  # (T,) its tendon springs


class Scribbles(Scene):
    """Living drawings.

    Attributes:
        screen: (x_min, y_min, x_max, y_max) metres of the page.
        rng: the tendon rule's generator (when no other is given).
        scribbles: live scribbles by id.

    Args:
        rng: tendons of new scribbles and the engine's wiggle seed.
        slots: scribbles that can live at once.
        max_nodes: nodes of the longest scribble.
        spacing: metres between the nodes of a scribble.
        screen_size: (width, height) metres of the page; its floor is near the bottom.
        record_forces: keep the net forces per frame (debug overlay).
    """

    name = "scribbles"
    score_name = "scribbles alive"

    def __init__(
        self,
        rng: np.random.Generator,
        *,
        slots: int = 4,
        max_nodes: int = 32,
        spacing: float = 0.16,
        screen_size: tuple[float, float] = (6.4, 4.8),
        record_forces: bool = False,
    ) -> None:
        assembly = Assembly()
        self._slots = [_allocate(assembly, s, max_nodes) for s in range(slots)]
        world = World(
            assembly.build(drag=0.01),
            SCRIBBLE_ENGINE,
            seed=int(rng.integers(2**63)),
            record_forces=record_forces,
        )
        width, height = screen_size
        super().__init__(world, view_size=screen_size, pull=Pull(8.0, 0.3, 6.0, 0.3))
        self.screen = (-0.5 * width, -_GROUND, 0.5 * width, height - _GROUND)
        self.rng = rng
        self.spacing = spacing
        self.max_nodes = max_nodes
        self.scribbles: dict[int, _Scribble] = {}
        self._next_id = 0

    def camera(self) -> tuple[float, float]:
        """The middle of the page."""
        x0, y0, x1, y1 = self.screen
        return (0.5 * (x0 + x1), 0.5 * (y0 + y1))

    def add_scribble(self, points: npt.ArrayLike, rng: np.random.Generator | None = None) -> int:
        """Bring a drawn curve to life and return its id (the oldest makes room if needed).

        Args:
            points: (P, 2) the curve, metres.
            rng: its tendons; None uses the scene's generator.
        """
        nodes = resample(points, self.spacing, self.max_nodes)
        busy = {s.slot for s in self.scribbles.values()}
        free = [slot for slot in range(len(self._slots)) if slot not in busy]
        if not free:
            oldest = min(self.scribbles)
            free = [self.scribbles[oldest].slot]
            self.remove_scribble(oldest)
        slot = free[0]
        first, pair_spring = self._slots[slot]
        index = first + np.arange(len(nodes))
        world = self.world
        world.reveal(index, nodes, np.zeros(2))
        bones = pair_spring[np.arange(len(nodes) - 1), np.arange(1, len(nodes))]
        world.rest_length[bones] = np.hypot(*np.diff(nodes, axis=0).T)
        world.switch(bones, on=True)
        scribble_id = self._next_id
        self._next_id += 1
        empty = np.zeros(0, dtype=np.int64)
        placeholder = Tendons.generate(nodes, self.rng if rng is None else rng)
        self.scribbles[scribble_id] = _Scribble(slot, index, bones, placeholder, empty)
        self._use_tendons(scribble_id, placeholder)
        self.score = len(self.scribbles)
        return scribble_id

    def regenerate_tendons(self, scribble_id: int, rng: np.random.Generator) -> None:
        """Roll new tendons for a scribble (a new personality for the same drawing).

        The relaxed tendon lengths come from the drawing's node positions.
        """
        scribble = self.scribbles[scribble_id]
        self.world.switch(scribble.springs, on=False)
        drawn = self.world.shape[scribble.nodes]
        self._use_tendons(scribble_id, Tendons.generate(drawn, rng))

    def remove_scribble(self, scribble_id: int) -> None:
        """Put a scribble away, freeing its slot."""
        scribble = self.scribbles.pop(scribble_id)
        world = self.world
        world.switch(np.concatenate([scribble.bones, scribble.springs]), on=False)
        world.park(scribble.nodes, at=_PARK + np.array([3.0 * scribble.slot, 0.0]))
        self.score = len(self.scribbles)

    def _use_tendons(self, scribble_id: int, tendons: Tendons) -> None:
        scribble = self.scribbles[scribble_id]
        _, pair_spring = self._slots[scribble.slot]
        springs = pair_spring[tendons.pairs[:, 0], tendons.pairs[:, 1]]
        self.world.shape[scribble.nodes] = self.world.positions[scribble.nodes]
        self.world.switch(springs, on=True)
        scribble.tendons, scribble.springs = tendons, springs

    def _before(
        self, inp: SceneInput, external: npt.NDArray[np.float64], events: list[SceneEvent]
    ) -> None:
        if inp.stroke is not None:
            events.append(SceneEvent("scribble", (self.add_scribble(inp.stroke),)))
        world = self.world
        for scribble in self.scribbles.values():
            world.rest_length[scribble.springs] = scribble.tendons.rest_lengths(world.time)
            external[scribble.nodes] += _grip(
                world.positions[scribble.nodes], world.velocities[scribble.nodes]
            )

    def _after(self, events: list[SceneEvent]) -> None:
        x0, y0, x1, y1 = self.screen
        margin = 3.0
        for scribble_id, scribble in list(self.scribbles.items()):
            x, y = self.world.positions[scribble.nodes].T
            if (
                x.min() > x1 + margin
                or x.max() < x0 - margin
                or min(y) > y1 + margin
                or max(y) < y0 - margin
            ):
                self.remove_scribble(scribble_id)
                events.append(SceneEvent("gone", (scribble_id,)))


def _grip(
    positions: npt.NDArray[np.float64], velocities: npt.NDArray[np.float64]
) -> npt.NDArray[np.float64]:
    """(n, 2) the page's grip on a scribble's nodes (like a worm's bristles).

    A node slides easily toward the head (node 0), hardly backward, and
    moderately sideways, so any rhythm of contraction and release crawls
    head first, and a lopsided one turns.

    Args:
        positions: (n, 2) the scribble's nodes, head first.
        velocities: (n, 2) their velocities.
    """
    behind = np.concatenate([positions[1:], positions[-1:]])
    ahead = np.concatenate([positions[:1], positions[:-1]])
    headward = ahead - behind
    headward /= np.maximum(np.hypot(*headward.T), 1e-9)[:, None]
    speed = np.sum(velocities * headward, axis=1)
    along = speed[:, None] * headward
    forward, backward, across = _GRIP
    grip = np.where(speed > 0.0, forward, backward)[:, None]
    return -grip * along - across * (velocities - along)


def _allocate(assembly: Assembly, slot: int, size: int) -> tuple[int, npt.NDArray[np.int64]]:
    """A parked scribble slot: ``size`` nodes and a spring for every pair of them.

    Returns:
        The slot's first node, and a (size, size) table of the spring joining
        nodes i < j of the slot (-1 elsewhere).
    """
    ink = _INKS[slot % len(_INKS)]
    park = _PARK + np.array([3.0 * slot, 0.0])
    nodes = [
        assembly.add_node(
            f"scribble{slot}.{k}",
            (float(park[0] + 0.1 * k), float(park[1])),
            mass=_MASS,
            radius=0.06 if k == 0 else 0.035,
            color=ink,
            active=False,
        )
        for k in range(size)
    ]
    table = np.full((size, size), -1, dtype=np.int64)
    for i in range(size):
        for j in range(i + 1, size):
            bone = j == i + 1
            strength, easing = _BONE if bone else (_TENDON, 0.0)
            spring = assembly.add_spring(
                nodes[i], nodes[j], 0.1 * (j - i), strength, easing, active=False
            )
            table[i, j] = spring
    return nodes[0], table
