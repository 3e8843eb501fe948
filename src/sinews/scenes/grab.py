"""Dragging a node with the mouse (Oh No, Kitten Avalanche!): a spring to the pointer.

A press grabs the visible node whose disc is nearest (within reach); while the button is
held, that node alone feels a damped spring toward the pointer, the same
spring whichever node it is. How the rest of the creature follows (or
resists) comes only from its masses and springs. Releasing lets go: the node
keeps its speed, so a quick drag flings.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from sinews.scenes.messages import SceneInput
from sinews.scenes.world import World

__all__ = ["Grab", "Pull"]


@dataclass(frozen=True)
class Pull:
    """The pointer's spring.

    Stable at the engine's explicit step dt when ``stiffness / m < (1 / dt)²``
    and ``damping / m < 1 / dt`` for the lightest grabbable node of mass m.

    Attributes:
        stiffness: newtons per metre between pointer and node.
        damping: newton-seconds per metre against the node's speed, so it
            settles on the pointer instead of swinging round it.
        max_force: newtons; the pull is never stronger (a pointer that jumps
            far does not yank a light node to pieces).
        reach: metres; a press grabs the visible node whose disc edge is nearest,
            if it is this close.
    """

    stiffness: float
    damping: float
    max_force: float
    reach: float


class Grab:
    """The mouse's hold on one node, updated every frame.

    Attributes:
        pull: the spring.
        node: the node held, or None.
    """

    def __init__(self, pull: Pull) -> None:
        self.pull = pull
        self.node: int | None = None
        self._was_pressed = False

    def update(self, inp: SceneInput, world: World, external: npt.NDArray[np.float64]) -> None:
        """Grab, hold or release from this frame's input; add the pull to ``external`` (N, 2)."""
        pressed = inp.pressed and inp.pointer is not None
        pointer = None if inp.pointer is None else np.asarray(inp.pointer, dtype=np.float64)
        if not pressed:
            self.node = None
        elif not self._was_pressed:
            self.node = self._nearest(world, pointer)
        if self.node is not None and not world.node_visible[self.node]:
            self.node = None  # the scene took it away (recycled)
        if self.node is not None and pointer is not None:
            pull = self.pull
            offset = pointer - world.positions[self.node]
            force = pull.stiffness * offset - pull.damping * world.velocities[self.node]
            size = float(np.hypot(*force))
            if size > pull.max_force:
                force *= pull.max_force / size
            external[self.node] += force
        self._was_pressed = pressed

    def _nearest(self, world: World, pointer: npt.NDArray[np.float64] | None) -> int | None:
        if pointer is None:
            return None
        distance = np.hypot(*(world.positions - pointer).T) - world.layout.body.radius
        distance[~world.node_visible] = np.inf
        node = int(np.argmin(distance))
        return node if distance[node] <= self.pull.reach else None
