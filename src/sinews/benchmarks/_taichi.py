"""Our dancers' frame loop written in Taichi, the way Taichi's mass-spring examples are.

As in Taichi's ``mass_spring_3d`` and cloth examples: state in ``ti.Vector.field``s,
one ``substep`` kernel launched from Python per frame, whose top-level loops run
in parallel — over (body, node) for the point forces and the integration, over
(body, spring) for the springs and the easing, with atomic adds into the node
forces. The maths is that of `sinews.springmass.kernels` for a batch without
attractions, drive or external forces (the benchmark's dancers: their actuators idle): gravity,
home (following the centroid), wiggle noise, springs, integration, easing,
drag, the floor, and the health check (a failed body is flagged and stops, but
is not put back to its last good pose: the benchmark's dancers never fail).
Only benchmarks import this module.
"""

from typing import Any

import numpy as np
import numpy.typing as npt
import taichi as ti
from taichi.lang.util import to_numpy_type

from sinews.springmass import BodyBatch, EngineParams
from sinews.springmass.kernels import EDGE_EPSILON, WIGGLE_CLOCK_NODE
from sinews.springmass.noise import unit_hash

__all__ = ["TaichiCrowd", "start"]

FloatArray = npt.NDArray[np.float64]
_GOLDEN, _MIX1, _MIX2, _AXIS = (
    0x9E3779B97F4A7C15, 0xBF58476D1CE4E5B9, 0x94D049BB133111EB, 0xD1B54A32D192ED03,
)  # fmt: skip


def start(threads: int) -> None:
    """Start Taichi's CPU back end with ``threads`` threads, float64."""
    ti.init(arch=ti.cpu, cpu_max_num_threads=threads, default_fp=ti.f64, log_level=ti.WARN)


@ti.func
def _hash(seed: ti.u64, node: ti.i32, axis: ti.i32, knot: ti.i32) -> ti.f64:
    """`sinews.springmass.noise.unit_hash` on Taichi's uint64."""
    z = (
        seed
        ^ (ti.cast(node, ti.u64) * ti.u64(_GOLDEN))
        ^ (ti.cast(axis, ti.u64) * ti.u64(_AXIS))
        ^ (ti.cast(knot, ti.u64) * ti.u64(_MIX2))
    ) + ti.u64(_GOLDEN)
    z = (z ^ (z >> ti.u64(30))) * ti.u64(_MIX1)
    z = (z ^ (z >> ti.u64(27))) * ti.u64(_MIX2)
    z = z ^ (z >> ti.u64(31))
    return ti.cast(z >> ti.u64(11), ti.f64) * (1.0 / 9007199254740992.0) * 2.0 - 1.0


@ti.data_oriented
class TaichiCrowd:
    """A `BodyBatch` in Taichi fields, stepped by one kernel launch per frame.

    Args:
        batch: P bodies without attractions (actuators are ignored: no drive).
        params: the engine settings.
        positions: (P, N, 2) starting positions (velocities start at zero).
    """

    def __init__(self, batch: BodyBatch, params: EngineParams, positions: FloatArray) -> None:
        if batch.n_attractions.any():
            raise ValueError("the Taichi crowd has no attractions")
        n_bodies, n, _ = batch.rest.shape
        n_edges = batch.edges.shape[1]
        self.params = params
        vec = ti.Vector.field
        self.pos, self.vel, self.force, self.delta, self.rest = (
            vec(2, ti.f64, shape=(n_bodies, n)) for _ in range(5)
        )
        self.mass, self.weight, self.radius, self.home, self.wiggle = (
            ti.field(ti.f64, shape=(n_bodies, n)) for _ in range(5)
        )
        self.edge = vec(2, ti.i32, shape=(n_bodies, n_edges))
        self.rest_length, self.strength, self.easing = (
            ti.field(ti.f64, shape=(n_bodies, n_edges)) for _ in range(3)
        )
        self.n_nodes, self.n_edges, self.clock, self.status = (
            ti.field(ti.i32, shape=n_bodies) for _ in range(4)
        )
        self.drag = ti.field(ti.f64, shape=n_bodies)
        self.seed = ti.field(ti.u64, shape=n_bodies)
        self.rest_centre, self.offset = (vec(2, ti.f64, shape=n_bodies) for _ in range(2))
        steps = params.wiggle_steps
        with np.errstate(over="ignore"):  # uint64 arithmetic wraps, as meant
            clock = (unit_hash(batch.seeds, WIGGLE_CLOCK_NODE, 2, 0) + 1.0) * 0.5 * steps
        rest_centre = np.array([b.rest[: b.n_nodes].mean(axis=0) for b in batch.bodies])
        for field, value in (
            (self.pos, positions), (self.vel, np.zeros_like(positions)), (self.rest, batch.rest),
            (self.mass, batch.mass), (self.weight, batch.weight), (self.radius, batch.radius),
            (self.home, batch.home), (self.wiggle, batch.wiggle), (self.edge, batch.edges),
            (self.rest_length, batch.rest_length), (self.strength, batch.strength),
            (self.easing, batch.easing), (self.n_nodes, batch.n_nodes),
            (self.n_edges, batch.n_edges), (self.drag, batch.drag), (self.seed, batch.seeds),
            (self.clock, clock.astype(np.int32) if params.wiggle_seeded_phase else 0 * clock),
            (self.rest_centre, rest_centre),
        ):  # fmt: skip
            field.from_numpy(np.ascontiguousarray(value, dtype=to_numpy_type(field.dtype)))

    def run(self, steps: int) -> None:
        """Advance every body ``steps`` frames (one kernel launch each) and wait."""
        p = self.params
        settings = (p.dt, p.gravity, p.floor, p.floor_y, p.friction, p.restitution,
                    *p.home_follow, p.wiggle_steps, p.max_speed)  # fmt: skip
        for step in range(steps):
            self.substep(step, *settings)
        ti.sync()

    def positions(self) -> FloatArray:
        """(P, N, 2) positions."""
        result: Any = self.pos.to_numpy()
        return np.asarray(result, dtype=np.float64)

    @ti.kernel
    def substep(  # type: ignore[no-untyped-def]
        self,
        step: ti.i32,
        dt: ti.f64,
        gravity: ti.f64,
        floor: ti.i32,
        floor_y: ti.f64,
        friction: ti.f64,
        restitution: ti.f64,
        follow_x: ti.f64,
        follow_y: ti.f64,
        wiggle_steps: ti.i32,
        max_speed: ti.f64,
    ):  # Taichi rejects a "-> None"
        for b in self.n_nodes:  # the centroid the home targets follow
            centre = ti.Vector([0.0, 0.0])
            for i in range(self.n_nodes[b]):
                centre += self.pos[b, i]
            centre = centre / self.n_nodes[b] - self.rest_centre[b]
            self.offset[b] = ti.Vector([follow_x * centre[0], follow_y * centre[1]])
        for b, i in self.pos:  # gravity, home, wiggle
            if i < self.n_nodes[b] and self.status[b] == 0:
                f = self.home[b, i] * (self.rest[b, i] + self.offset[b] - self.pos[b, i])
                f[1] -= gravity * self.mass[b, i] * self.weight[b, i]
                amp = self.wiggle[b, i]
                if amp != 0.0:
                    t = step + self.clock[b]
                    knot = t // wiggle_steps
                    x = (t - knot * wiggle_steps) / wiggle_steps
                    blend = x * x * (3.0 - 2.0 * x)
                    seed = self.seed[b]
                    a0, a1 = _hash(seed, i, 0, knot), _hash(seed, i, 0, knot + 1)
                    b0, b1 = _hash(seed, i, 1, knot), _hash(seed, i, 1, knot + 1)
                    f += amp * ti.Vector([a0 + (a1 - a0) * blend, b0 + (b1 - b0) * blend])
                self.force[b, i] = f
        for b, e in self.edge:  # springs
            if e < self.n_edges[b] and self.status[b] == 0:
                i, j = self.edge[b, e][0], self.edge[b, e][1]
                d = self.pos[b, j] - self.pos[b, i]
                length = d.norm() + EDGE_EPSILON
                f = self.strength[b, e] * (length - self.rest_length[b, e]) / length * d
                self.force[b, i] += f
                self.force[b, j] -= f
        for b, i in self.pos:  # integrate
            if i < self.n_nodes[b] and self.status[b] == 0:
                self.vel[b, i] += self.force[b, i] * (dt / self.mass[b, i])
                self.pos[b, i] += self.vel[b, i] * dt
                self.delta[b, i] = ti.Vector([0.0, 0.0])
        for b, e in self.edge:  # easing, all from the same pose
            if e < self.n_edges[b] and self.status[b] == 0 and self.easing[b, e] > 0.0:
                i, j = self.edge[b, e][0], self.edge[b, e][1]
                d = self.pos[b, j] - self.pos[b, i]
                length = d.norm() + EDGE_EPSILON
                c = 0.5 * self.easing[b, e] * (length - self.rest_length[b, e]) / length * d
                self.delta[b, i] += c
                self.delta[b, j] -= c
        for b, i in self.pos:  # apply the easing, drag, floor, health check
            if i < self.n_nodes[b] and self.status[b] == 0:
                self.pos[b, i] += self.delta[b, i]
                self.vel[b, i] *= 1.0 - self.drag[b]
                ground = floor_y + self.radius[b, i]
                if floor and self.pos[b, i][1] < ground:
                    self.pos[b, i][1] = ground
                    if self.vel[b, i][1] < 0.0:
                        self.vel[b, i][1] = -restitution * self.vel[b, i][1]
                    self.vel[b, i][0] *= 1.0 - friction
                speed2 = self.vel[b, i].norm_sqr()
                if not (ti.math.isinf(speed2) or ti.math.isnan(speed2)):
                    if speed2 > max_speed * max_speed:
                        self.status[b] = 2
                else:
                    self.status[b] = 1
