"""The playable scene: a `World` plus game logic, steppable live or played headless.

Every frame, `Scene.step` lets the scene's logic switch parts of the body
and add its forces, adds the mouse's pull, takes one engine step and lets the
logic react (links, breaks, flings). A live driver calls `step` at 60 Hz;
`record` and `play` run it headless with a `Script` standing in for the
player.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from typing import ClassVar

import numpy as np
import numpy.typing as npt

from sinews.limits import MAX_SECONDS, check_number
from sinews.scenes.grab import Grab, Pull
from sinews.scenes.messages import NO_INPUT, SceneEvent, SceneFrame, SceneInput, SceneRun, Script
from sinews.scenes.world import World
from sinews.trajectory import Trajectory

__all__ = ["Scene"]

Point = tuple[float, float]


class Scene(ABC):
    """A game scene on the spring-mass engine.

    Attributes:
        world: the merged body being simulated.
        view_size: (width, height) metres the camera shows.
        grab: the mouse's hold on a node.
        score: the scene's counter (see `score_name`).

    Args:
        world: the merged body, ready to step.
        view_size: (width, height) metres the camera shows.
        pull: the mouse's spring for dragging nodes.
    """

    name: ClassVar[str]
    """The scene's command-line name."""
    score_name: ClassVar[str]
    """What `score` counts."""

    def __init__(self, world: World, *, view_size: tuple[float, float], pull: Pull) -> None:
        self.world = world
        self.view_size = view_size
        self.grab = Grab(pull)
        self.score = 0

    @abstractmethod
    def _before(
        self, inp: SceneInput, external: npt.NDArray[np.float64], events: list[SceneEvent]
    ) -> None:
        """Game logic before the engine step: switch parts, add forces to ``external`` (N, 2)."""

    @abstractmethod
    def _after(self, events: list[SceneEvent]) -> None:
        """Game logic after the engine step: react to where everything went."""

    @abstractmethod
    def camera(self) -> Point:
        """(x, y) metres the view is centred on now."""

    def step(self, inp: SceneInput = NO_INPUT) -> SceneFrame:
        """Advance one frame (1/60 s) with the player's input and return the new frame."""
        external = np.zeros((self.world.n_nodes, 2))
        events: list[SceneEvent] = []
        self._before(inp, external, events)
        self.grab.update(inp, self.world, external)
        forces = self.world.step(external)
        self._after(events)
        return self.frame(tuple(events), forces)

    def frame(
        self,
        events: tuple[SceneEvent, ...] = (),
        forces: npt.NDArray[np.float32] | None = None,
    ) -> SceneFrame:
        """The scene as it is now (arrays are copies)."""
        world = self.world
        return SceneFrame(
            step=world.frame,
            time=world.time,
            positions=world.positions.astype(np.float32),
            node_visible=world.node_visible.copy(),
            edge_visible=world.edge_visible.copy(),
            camera=self.camera(),
            score=self.score,
            events=events,
            grabbed=self.grab.node,
            forces=None if forces is None else forces.copy(),
        )

    def record(self, seconds: float, script: Script | None = None) -> SceneRun:
        """Play ``seconds`` from where the scene is, ``script`` standing in for the player.

        Args:
            seconds: how long to play.
            script: input for each step given the latest frame; None plays
                without input (the scene plays itself).
        """
        check_number("seconds", seconds, 0.0, MAX_SECONDS)
        n_steps = round(seconds / self.world.frame_dt)
        frames = [self.frame()]
        events: list[tuple[int, SceneEvent]] = []
        for k in range(1, n_steps + 1):
            frames.append(self.step(NO_INPUT if script is None else script(frames[-1])))
            events += [(k, event) for event in frames[-1].events]
        return SceneRun(
            scene=self.name,
            score_name=self.score_name,
            trajectory=self._trajectory(frames),
            camera=np.array([f.camera for f in frames], dtype=np.float64),
            view_size=self.view_size,
            score=np.array([f.score for f in frames], dtype=np.int64),
            events=tuple(events),
        )

    def play(self, seconds: float, script: Script | None = None) -> Trajectory:
        """`record` and keep only the trajectory."""
        return self.record(seconds, script).trajectory

    def _trajectory(self, frames: list[SceneFrame]) -> Trajectory:
        layout = self.world.layout
        body = layout.body
        forces = None
        if self.world.record_forces:
            # The trajectory's convention: forces[k] acted in the step after frame k.
            after = [f.forces for f in frames[1:] if f.forces is not None]
            forces = np.stack([*after, np.zeros_like(frames[0].positions)])
        return Trajectory(
            positions=np.stack([f.positions for f in frames]),
            fps=1.0 / self.world.frame_dt,
            edges=body.edges,
            node_names=body.names,
            radii=body.radius.astype(np.float32),
            colors=body.colors,
            forces=forces,
            node_visible=np.stack([f.node_visible for f in frames]),
            edge_visible=np.stack([f.edge_visible for f in frames]),
            node_shapes=layout.node_shapes,
            failed=self.world.failed,
        )
