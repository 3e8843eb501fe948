"""A scene's merged body on the spring-mass engine, stepped one frame at a time.

The `World` owns the one-body `BodyBatch` and its `SimState` and offers the
few operations scene logic performs *between* engine steps: switching
springs and attraction pairs on and off, parking spare nodes (weightless,
still, hidden) and revealing them, and letting each creature's home pull
follow that creature. Everything that moves is moved by `simulate`; the
scene only changes the body's arrays and, when a part appears, where it is.
"""

from __future__ import annotations

from collections.abc import Sequence

import numba
import numpy as np
import numpy.typing as npt

from sinews.scenes.assembly import Layout
from sinews.springmass import BodyBatch, EngineParams, simulate

__all__ = ["World"]

FloatArray = npt.NDArray[np.float64]
Index = slice | int | npt.NDArray[np.int64] | Sequence[int]


class World:
    """One merged body, its engine settings and where it is now.

    The arrays below are views into the batch (``*[0]``), so writing them
    changes the body the next step simulates.

    Attributes:
        layout: the merged body with every part's "on" values.
        params: engine settings.
        batch: the one-body batch the engine steps.
        weight, home, rest: (N,) and (N, 2) views of the batch's node arrays.
        strength, rest_length, easing: (E,) views of the batch's spring arrays.
        attraction_strength: (A,) view of the batch's attraction strengths.
        node_visible: (N,) which nodes are drawn.
        edge_visible: (E,) which springs are drawn.
        record_forces: whether `step` returns the net forces (debug overlay).
        substeps: engine steps per frame.

    Args:
        layout: what `Assembly.build` made; inactive parts start switched off.
        params: engine settings; ``params.dt`` is one engine step.
        seed: the engine's wiggle-noise seed.
        substeps: engine steps per frame (stiffer bodies need shorter steps).
        record_forces: return the net force on every node from `step`.
    """

    def __init__(
        self,
        layout: Layout,
        params: EngineParams,
        *,
        seed: int,
        substeps: int = 1,
        record_forces: bool = False,
    ) -> None:
        self.layout = layout
        self.params = params
        self.substeps = substeps
        self.record_forces = record_forces
        self.batch = BodyBatch.from_bodies([layout.body], seeds=[seed])
        self.state = self.batch.initial_state()
        body = layout.body
        self.shape = body.rest.copy()
        self.weight = self.batch.weight[0]
        self.home = self.batch.home[0]
        self.rest = self.batch.rest[0]
        self.strength = self.batch.strength[0]
        self.rest_length = self.batch.rest_length[0]
        self.easing = self.batch.easing[0]
        self.attraction_strength = self.batch.attraction_strength[0]
        self.attraction_strength[:] = 0.0
        self.node_visible = np.ones(body.n_nodes, dtype=bool)
        self.edge_visible = np.ones(body.n_edges, dtype=bool)
        self.park(np.flatnonzero(~layout.node_active))
        self.switch(np.flatnonzero(~layout.edge_active), on=False)

    @property
    def n_nodes(self) -> int:
        """Nodes N of the merged body."""
        return self.layout.body.n_nodes

    @property
    def positions(self) -> FloatArray:
        """(N, 2) metres, a writable view of the state."""
        return self.state.positions[0]

    @property
    def velocities(self) -> FloatArray:
        """(N, 2) metres per second, a writable view of the state."""
        return self.state.velocities[0]

    @property
    def frame_dt(self) -> float:
        """Seconds per frame (`substeps` engine steps)."""
        return self.params.dt * self.substeps

    @property
    def frame(self) -> int:
        """Frames simulated so far."""
        return self.state.step // self.substeps

    @property
    def time(self) -> float:
        """Seconds simulated so far."""
        return self.state.step * self.params.dt

    @property
    def failed(self) -> bool:
        """Whether the engine froze the scene (a node blew up or ran away)."""
        return bool(self.state.failed[0])

    def step(self, external: FloatArray) -> npt.NDArray[np.float32] | None:
        """Advance one frame with ``external`` (N, 2) newtons on the nodes throughout.

        The engine runs on one thread: a one-body batch gains nothing from
        more, and on a busy machine a parallel launch per frame cost 3 ms
        instead of 0.1 ms (measured, 300 nodes).

        Returns:
            (N, 2) the net force on each node in the frame's first engine step
            if ``record_forces``, else None.
        """
        threads = numba.get_num_threads()
        numba.set_num_threads(1)
        try:
            self.state, recording = simulate(
                self.batch,
                self.state,
                self.substeps,
                self.params,
                external=external[None],
                record=self.record_forces,
                record_stride=self.substeps,
                record_forces=self.record_forces,
            )
        finally:
            numba.set_num_threads(threads)
        if recording is None or recording.forces is None:
            return None
        return recording.forces[0, 0]

    def switch(self, edges: Index, *, on: bool, visible: bool | None = None) -> None:
        """Turn springs on (their layout strength and easing) or off (none); show them if on.

        Args:
            edges: which springs.
            on: on or off.
            visible: whether to draw them (default: drawn when on).
        """
        body = self.layout.body
        self.strength[edges] = body.strength[edges] if on else 0.0
        self.easing[edges] = body.easing[edges] if on else 0.0
        self.edge_visible[edges] = on if visible is None else visible

    def park(self, nodes: Index, at: FloatArray | None = None) -> None:
        """Hide nodes and make them weightless and still, where they are or ``at`` (n, 2).

        Their home targets move with them, so nothing pulls them back.
        """
        if at is not None:
            self.positions[nodes] = at
        self.rest[nodes] = self.positions[nodes]
        self.weight[nodes] = 0.0
        self.velocities[nodes] = 0.0
        self.node_visible[nodes] = False

    def reveal(self, nodes: Index, positions: FloatArray, velocity: FloatArray) -> None:
        """Show parked nodes at ``positions`` (n, 2) moving at ``velocity`` (2,) or (n, 2).

        Their home targets move with them, so nothing pulls them back.
        """
        self.positions[nodes] = positions
        self.rest[nodes] = positions
        self.velocities[nodes] = velocity
        self.weight[nodes] = self.layout.body.weight[nodes]
        self.node_visible[nodes] = True

    def follow_home(self, parts: Sequence[slice]) -> None:
        """Let each part's home pull follow that part: it keeps its shape but drifts freely.

        The home target of every node of a part is its shape (`shape`)
        shifted by the home-weighted mean offset of the part, so the home
        forces of a part sum to zero: they hold the shape and never push the
        part as a whole (the engine's ``home_follow`` follows the centroid
        of the whole merged body instead).
        """
        for nodes in parts:
            k = self.home[nodes]
            total = float(k.sum())
            if total <= 0.0:
                continue
            offset = k @ (self.positions[nodes] - self.shape[nodes]) / total
            self.rest[nodes] = self.shape[nodes] + offset
