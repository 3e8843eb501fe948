"""Oh No, Kitten Avalanche! (seed 000, "Novel Interaction Affordances").

Gelatinous kittens tumble onto the screen from above and land on the floor
(through each other: the engine, like the paper's, has no collisions); the
player drags any of their nodes to fling them off-screen. A kitten leaves
once it has been on screen and then every one of its nodes is outside the
screen box; it counts as flung if the player ever held it (one that
wobbles off by itself has wandered). Either way it is parked and later
comes back as a new arrival. Arrivals come faster and faster (a gentle
difficulty ramp).

All kittens live in one pre-allocated pool inside the scene's one body;
parked kittens are weightless, still and hidden far away.
"""

from __future__ import annotations

from collections import deque

import numpy as np
import numpy.typing as npt

from sinews.scenes.assembly import Assembly, Part
from sinews.scenes.grab import Pull
from sinews.scenes.kitten import KITTEN_SHAPES, kitten
from sinews.scenes.messages import SceneEvent, SceneInput
from sinews.scenes.scene import Scene
from sinews.scenes.world import World
from sinews.springmass import EngineParams

__all__ = ["KITTEN_ENGINE", "KITTEN_PULL", "KITTEN_SUBSTEPS", "KittenAvalanche"]

KITTEN_SUBSTEPS = 8
"""Engine steps per 60 Hz frame: short steps let light paws and tails carry springs
stiff enough to hold a kitten up (at 4 they sagged flat under their weight)."""
KITTEN_ENGINE = EngineParams(
    dt=1.0 / (60.0 * KITTEN_SUBSTEPS), floor=True, friction=0.035, restitution=0.15
)
"""Earth gravity, a bouncy floor at y = 0, 480 engine steps per second."""
KITTEN_PULL = Pull(stiffness=120.0, damping=3.0, max_force=90.0, reach=0.3)
"""The mouse: up to about four times a kitten's weight; stable on the lightest kitten
node (about 0.04 kg) at the 480 Hz engine step."""
_GROUND = 0.3
"""Metres of ground below the floor line at the bottom of the screen."""
_PARK = np.array([1000.0, 1000.0])
"""Where parked kittens wait, far from the screen (each 3 m from the last)."""


class KittenAvalanche(Scene):
    """Kittens rain down; drag them off-screen.

    Attributes:
        parts: where each kitten of the pool sits in the merged body.
        screen: (x_min, y_min, x_max, y_max) metres of the screen box.
        interval: seconds until the arrival after next.
        on_screen: (K,) which kittens are out and have entered the screen.
        held: (K,) which kittens the player has grabbed since they arrived.

    Args:
        rng: kitten looks, arrival places, spins and the engine's wiggle seed.
        pool: kittens pre-allocated.
        screen_size: (width, height) metres; the floor is a little above the bottom edge.
        first_interval: seconds between the first arrivals.
        ramp: each arrival shortens the interval by this factor ...
        min_interval: ... down to this many seconds.
        record_forces: keep the net forces per frame (debug overlay).
    """

    name = "kittens"
    score_name = "kittens flung"

    def __init__(
        self,
        rng: np.random.Generator,
        *,
        pool: int = 10,
        screen_size: tuple[float, float] = (4.0, 3.0),
        first_interval: float = 1.2,
        ramp: float = 0.92,
        min_interval: float = 0.5,
        record_forces: bool = False,
    ) -> None:
        assembly = Assembly()
        self.parts: list[Part] = []
        for k in range(pool):
            body = kitten(rng, dt=KITTEN_ENGINE.dt)
            self.parts.append(assembly.add_body(f"kitten{k}", body, shapes=KITTEN_SHAPES))
        layout = assembly.build(drag=body.drag)
        world = World(
            layout,
            KITTEN_ENGINE,
            seed=int(rng.integers(2**63)),
            substeps=KITTEN_SUBSTEPS,
            record_forces=record_forces,
        )
        width, height = screen_size
        super().__init__(world, view_size=screen_size, pull=KITTEN_PULL)
        self.screen = (-0.5 * width, -_GROUND, 0.5 * width, height - _GROUND)
        self.rng = rng
        self.interval = first_interval
        self._ramp = (ramp, min_interval)
        self._next_arrival = 0.2
        self._waiting = deque(range(pool))
        self.on_screen = np.zeros(pool, dtype=bool)
        self.held = np.zeros(pool, dtype=bool)
        self._out = np.zeros(pool, dtype=bool)
        for k in range(pool):
            self._park(k)

    def camera(self) -> tuple[float, float]:
        """The middle of the screen."""
        x0, y0, x1, y1 = self.screen
        return (0.5 * (x0 + x1), 0.5 * (y0 + y1))

    def kitten_of(self, node: int) -> int:
        """The kitten a node belongs to."""
        return next(
            k for k, part in enumerate(self.parts) if part.nodes.start <= node < part.nodes.stop
        )

    def _park(self, k: int) -> None:
        nodes = self.parts[k].nodes
        spot = self.world.shape[nodes] + _PARK + [3.0 * k, 0.0]
        self.world.park(nodes, at=spot)
        self._out[k] = False
        self.on_screen[k] = False
        self.held[k] = False

    def _arrive(self, k: int) -> None:
        """Drop kitten ``k`` in from above the screen, turned and spinning."""
        x0, _, x1, y1 = self.screen
        nodes = self.parts[k].nodes
        shape = self.world.shape[nodes]
        local = shape - shape.mean(axis=0)
        angle = self.rng.uniform(-np.pi, np.pi)
        c, s = np.cos(angle), np.sin(angle)
        local = local @ np.array([[c, s], [-s, c]])
        centre = np.array([self.rng.uniform(0.7 * x0, 0.7 * x1), y1 + 0.6])
        spin = self.rng.uniform(-6.0, 6.0)
        velocity = np.array([self.rng.uniform(-0.8, 0.8), -1.0]) + spin * local @ [[0, 1], [-1, 0]]
        self.world.reveal(nodes, centre + local, velocity)
        self._out[k] = True

    def _before(
        self, inp: SceneInput, external: npt.NDArray[np.float64], events: list[SceneEvent]
    ) -> None:
        if self.world.time + 1e-9 >= self._next_arrival and self._waiting:
            k = self._waiting.popleft()
            self._arrive(k)
            events.append(SceneEvent("spawn", (k,)))
            ramp, shortest = self._ramp
            self._next_arrival = self.world.time + self.interval
            self.interval = max(shortest, self.interval * ramp)

    def _after(self, events: list[SceneEvent]) -> None:
        if self.grab.node is not None:
            self.held[self.kitten_of(self.grab.node)] = True
        x0, y0, x1, y1 = self.screen
        pos = self.world.positions
        inside = (pos[:, 0] >= x0) & (pos[:, 0] <= x1) & (pos[:, 1] >= y0) & (pos[:, 1] <= y1)
        for k, part in enumerate(self.parts):
            if not self._out[k]:
                continue
            anywhere = bool(inside[part.nodes].any())
            if anywhere:
                self.on_screen[k] = True
            elif self.on_screen[k]:
                self.score += int(self.held[k])
                events.append(SceneEvent("flung" if self.held[k] else "wandered", (k,)))
                self._park(k)
                self._waiting.append(k)
