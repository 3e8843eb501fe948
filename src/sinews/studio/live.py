"""The stage dancer simulated live, a frame at a time, while a person drags one of its nodes.

As in Kitten Avalanche (seed 000), a grabbed node is pulled toward the
mouse by an external force and the rest of the body follows through its
springs, so which node is grabbed decides how the body resists: a hand
stretches its arm, the pelvis hauls the whole dancer along. The pull is a
critically damped spring on the grabbed node, `GRAB_HZ` for `GRAB_MASSES`
times the node's mass (more would be unstable at the engine's 60 Hz
explicit step), and never stronger than `MAX_PULL_G` times the body's weight.

The live simulation starts from exactly what `sinews.experiments.dancers.simulate.dance`
starts from (`prepare_dance`: the same body, wiggle seed, delayed music drive and
beat phase), so until a node is grabbed it moves bit for bit like the recorded dance, and it follows
the page's audio clock: asked for frame k, it steps from where it is to k
(or starts again from frame 0 when the clock went back).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from sinews.dancers import DANCER_ENGINE
from sinews.experiments.dancers.simulate import prepare_dance
from sinews.springmass import Recording, SimState, simulate
from sinews.studio.motion import StageDancer

__all__ = ["GRAB_HZ", "GRAB_MASSES", "MAX_PULLED_STEPS", "MAX_PULL_G", "Grab", "LiveDancer"]

GRAB_HZ = 3.0
"""Natural frequency of the mouse's pull."""
GRAB_MASSES = 2.0
"""The pull is tuned for this many times the grabbed node's mass."""
MAX_PULL_G = 6.0
"""The pull never exceeds this many times the body's weight."""
MAX_PULLED_STEPS = 12
"""Most steps simulated with the pull in one call (the page asks every animation frame)."""


@dataclass(frozen=True)
class Grab:
    """A node held by the mouse.

    Attributes:
        node: index of the grabbed node.
        target: (x, y) metres where the mouse is.
    """

    node: int
    target: tuple[float, float]


class LiveDancer:
    """One dancer stepped on demand, optionally pulled by the mouse.

    Args:
        dancer: the stage dancer (genome with slider changes, seed, song).
    """

    def __init__(self, dancer: StageDancer) -> None:
        setup = prepare_dance(
            [dancer.genome], dancer.seconds, music=dancer.music,
            seeds=[int(dancer.individual.seed or 0)],
        )  # fmt: skip
        body = setup.batch.bodies[0]
        self.batch = setup.batch
        self.n_nodes = body.n_nodes
        self.frames = setup.n_steps + 1
        self._drive = setup.drive
        self._phase = setup.phase
        self._pose = setup.pose
        self._mass = body.mass
        self._max_pull = MAX_PULL_G * float(body.mass.sum()) * DANCER_ENGINE.gravity
        self.state = self.batch.initial_state()
        self.forces = np.zeros((self.n_nodes, 2), dtype=np.float32)

    @property
    def frame(self) -> int:
        """The frame the dancer is at."""
        return self.state.step

    @property
    def positions(self) -> npt.NDArray[np.float32]:
        """(N, 2) metres, where the nodes are now."""
        return self.state.positions[0].astype(np.float32)

    def step_to(self, frame: int, grab: Grab | None = None) -> None:
        """Advance to ``frame`` (clipped to the dance), pulled by ``grab`` on the way.

        A frame before the current one starts the dance again from frame 0
        (the song was rewound or looped). A long jump forward is simulated
        without the pull except for its last `MAX_PULLED_STEPS` steps.
        """
        frame = min(max(int(frame), 0), self.frames - 1)
        if frame < self.state.step:
            self.state = self.batch.initial_state()
        free = frame - self.state.step - (MAX_PULLED_STEPS if grab else 1)
        if free > 0:
            self.state, _ = self._simulate(free, None, record=False)
        while self.state.step < frame:
            self.state, recording = self._simulate(1, grab, record=True)
            assert recording is not None and recording.forces is not None
            self.forces = recording.forces[0, 0]

    def _simulate(
        self, n_steps: int, grab: Grab | None, *, record: bool
    ) -> tuple[SimState, Recording | None]:
        return simulate(
            self.batch,
            self.state,
            n_steps,
            DANCER_ENGINE,
            external=None if grab is None else self._pull(grab),
            drive=self._drive,
            phase=self._phase,
            pose=self._pose,
            record=record,
            record_forces=record,
        )

    def _pull(self, grab: Grab) -> npt.NDArray[np.float64]:
        """(1, N, 2) the mouse's force: a critically damped spring on the grabbed node."""
        omega = 2.0 * math.pi * GRAB_HZ
        node = min(max(grab.node, 0), self.n_nodes - 1)
        offset = np.asarray(grab.target, dtype=np.float64) - self.state.positions[0, node]
        velocity = self.state.velocities[0, node]
        mass = GRAB_MASSES * self._mass[node]
        force = mass * (omega**2 * offset - 2.0 * omega * velocity)
        size = float(np.hypot(*force))
        if size > self._max_pull:
            force *= self._max_pull / size
        external = np.zeros((1, self.batch.rest.shape[1], 2))
        external[0, node] = np.nan_to_num(force)
        return external
