"""Falling for You (seed 000, "Prior Work", Fig. 3): ragdolls fall, long for each other, link.

Dolls fall slowly through the sky, pushed about by gentle gusts. Love is a
directed boolean: when a doll's beloved has a hand within reach, the
lover's nearest free hand is pulled hard toward it, and the whole body
follows through its springs. When two mutually attracted hands meet they
link and a heart balloon lifts the couple; later a baby comes, holding a
parent's free hand, with a balloon of its own, and the family rises
(`sinews.scenes.romance`).

The left/right keys push every node of the main doll, the one the camera
follows. Only the player is strong enough to pull a couple apart: a link
breaks when its spring pulls harder than the break force, which gusts,
balloons and longing never reach (tested over long runs).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt

from sinews.scenes.assembly import Assembly, Part
from sinews.scenes.dolls import doll
from sinews.scenes.grab import Pull
from sinews.scenes.messages import SceneEvent, SceneInput
from sinews.scenes.romance import Romance, RomanceTuning
from sinews.scenes.scene import Scene
from sinews.scenes.world import World
from sinews.springmass import EngineParams
from sinews.springmass.noise import smoothstep, unit_hash

__all__ = ["FALLING_ENGINE", "FALLING_PULL", "FallingForYou", "FallingTuning"]

FALLING_ENGINE = EngineParams(floor=False)
"""The sky: no floor. Each doll's home pull follows that doll (`World.follow_home`)."""
FALLING_PULL = Pull(stiffness=150.0, damping=8.0, max_force=300.0, reach=0.3)
"""The mouse, if the player drags a doll instead of pushing."""
_DRAG = 0.04
"""Velocity lost per frame: dolls fall at a leisurely third of a metre per second."""
_PARK = np.array([-1000.0, 1000.0])


@dataclass(frozen=True)
class FallingTuning:
    """The forces of the scene besides love (newtons, metres, seconds).

    Attributes:
        push: force on every node of the main doll per unit of input.
        gust: typical acceleration of each doll's gusts, m/s².
        gust_period: seconds between gust changes.
        far: metres from the camera beyond which a lone doll comes back from
            above and a lost balloon or baby is put away.
        romance: attraction, links, balloons and babies.
    """

    push: float = 30.0
    gust: float = 0.35
    gust_period: float = 2.0
    far: float = 9.0
    romance: RomanceTuning = field(default_factory=RomanceTuning)


class FallingForYou(Scene):
    """Ragdolls falling in love; the camera follows doll 0, the player's.

    Attributes:
        dolls: where each doll sits in the merged body: grown-ups, then babies.
        n_adults: how many of `dolls` are grown-ups.
        romance: who loves whom, who holds whose hand, balloons and babies.
        tuning: the forces.

    Args:
        rng: the dolls, who loves whom, where they start, gusts, wiggle seed.
        n_adults: grown-up dolls (at least 2).
        n_babies: babies that may be born.
        tuning: the forces.
        loves: (n_adults, n_adults) bool, ``loves[a, b]``: doll a is attracted
            to doll b; None chooses at random (doll 0 always has a partner).
        record_forces: keep the net forces per frame (debug overlay).
    """

    name = "falling-for-you"
    score_name = "couples formed"

    def __init__(
        self,
        rng: np.random.Generator,
        *,
        n_adults: int = 5,
        n_babies: int = 2,
        tuning: FallingTuning | None = None,
        loves: npt.ArrayLike | None = None,
        record_forces: bool = False,
    ) -> None:
        self.tuning = tuning = tuning or FallingTuning()
        self.n_adults = n_adults
        assembly = Assembly()
        dolls = []
        for c in range(n_adults + n_babies):
            grown = c < n_adults
            body = doll(rng, scale=1.0 if grown else 0.55)
            name = f"doll{c}" if grown else f"baby{c - n_adults}"
            dolls.append((assembly.add_body(name, body, active=grown), body))
        self.dolls: list[Part] = [part for part, _ in dolls]
        self.romance = Romance.build(rng, assembly, dolls, n_adults, tuning.romance, loves)
        world = World(
            assembly.build(drag=_DRAG),
            FALLING_ENGINE,
            seed=int(rng.integers(2**63)),
            record_forces=record_forces,
        )
        for start, part in zip(_starts(rng, n_adults), self.dolls, strict=False):
            world.positions[part.nodes] = world.shape[part.nodes] + start
        for part in self.dolls[n_adults:]:
            world.park(part.nodes, at=world.shape[part.nodes] + _PARK)
        super().__init__(world, view_size=(6.4, 4.8), pull=FALLING_PULL)
        self.rng = rng
        self._gust_seed = np.uint64(rng.integers(2**63))

    def camera(self) -> tuple[float, float]:
        """The main doll's centroid."""
        x, y = self.world.positions[self.dolls[0].nodes].mean(axis=0)
        return (float(x), float(y))

    def _before(
        self, inp: SceneInput, external: npt.NDArray[np.float64], events: list[SceneEvent]
    ) -> None:
        world = self.world
        world.follow_home([part.nodes for part in self.dolls])
        self._gusts(external)
        push = self.tuning.push * float(np.clip(inp.push, -1.0, 1.0))
        external[self.dolls[0].nodes, 0] += push
        self.romance.reach_out(world)
        self._recycle(events)

    def _after(self, events: list[SceneEvent]) -> None:
        self.romance.hold_and_let_go(self.world, events)
        self.score = self.romance.couples_formed

    def _gusts(self, external: npt.NDArray[np.float64]) -> None:
        """Each doll's own smooth gust: one acceleration for all its nodes (no strain)."""
        t = self.world.time / self.tuning.gust_period
        knot = int(t)
        dolls = np.arange(len(self.dolls))[:, None]
        axes = np.arange(2)[None, :]
        knots = np.array([[knot, knot + 1]]).T[:, :, None]  # (2, 1, 1)
        before, after = unit_hash(self._gust_seed, dolls, axes, knots)
        accel = self.tuning.gust * (before + (after - before) * smoothstep(t - knot)) * [1.0, 0.4]
        mass = self.world.layout.body.mass
        for part, doll_accel in zip(self.dolls, accel, strict=True):
            external[part.nodes] += mass[part.nodes, None] * doll_accel

    def _recycle(self, events: list[SceneEvent]) -> None:
        """Lone dolls far from the camera drift back in from above; lost balloons vanish."""
        world, far = self.world, self.tuning.far
        camera = np.array(self.camera())
        for c in range(1, self.n_adults):
            nodes = self.dolls[c].nodes
            centre = world.positions[nodes].mean(axis=0)
            if self.romance.is_single(c) and np.hypot(*(centre - camera)) > far:
                x = camera[0] + self.rng.uniform(-2.5, 2.5)
                shape = world.shape[nodes]
                spot = shape - shape.mean(axis=0) + [x, camera[1] + 4.5]
                world.reveal(nodes, spot, np.array([0.0, -0.3]))
                events.append(SceneEvent("spawn", (c,)))
        self.romance.tidy(world, camera, far, events)


def _starts(rng: np.random.Generator, n_adults: int) -> npt.NDArray[np.float64]:
    """(n_adults, 2) offsets: the main doll at the origin, the others on a loose ring."""
    angles = np.linspace(0.0, 2.0 * np.pi, n_adults - 1, endpoint=False) + rng.uniform(0, 2 * np.pi)
    angles += rng.uniform(-0.3, 0.3, n_adults - 1)
    radius = rng.uniform(2.0, 3.0, n_adults - 1)
    ring = np.stack([np.cos(angles), 0.75 * np.sin(angles)], axis=1) * radius[:, None]
    return np.vstack([[0.0, 0.0], ring])
