"""The frame loop in plain numpy, vectorised over bodies: the kernel's test oracle.

Same maths as `sinews.springmass.kernels.simulate_kernel`, same argument list,
written for clarity rather than speed (it loops over steps in Python and uses
``np.add.at`` for the scatter). Benchmarks measure the kernel against it.
Actuators are the one part it shares with the kernel: it calls the pure-Python
body of `kernels.actuate` (their force patterns have tests of their own).
"""

from __future__ import annotations

import numpy as np

from sinews.springmass.kernels import ATTRACTION_SOFTNESS, EDGE_EPSILON, WIGGLE_CLOCK_NODE, actuate
from sinews.springmass.noise import smoothstep, unit_hash

__all__ = ["simulate_reference"]


def _scatter(target: np.ndarray, body: np.ndarray, node: np.ndarray, value: np.ndarray) -> None:
    np.add.at(target, (body, node), value)


def simulate_reference(
    pos,
    vel,
    status,
    failed_step,
    n_nodes,
    n_edges,
    n_attr,
    rest,
    mass,
    weight,
    radius,
    home,
    wiggle,
    edges,
    rest_length,
    strength,
    easing,
    attraction,
    attr_strength,
    attr_reach,
    drag,
    seeds,
    n_act,
    act_node,
    act_kind,
    act_channels,
    act_strength,
    act_custom,
    pose_basis,
    drive,
    phase,
    pose,
    external,
    start_step,
    n_steps,
    dt,
    gravity,
    floor,
    floor_y,
    friction,
    restitution,
    follow_x,
    follow_y,
    wiggle_steps,
    wiggle_seeded_phase,
    max_speed,
    record_stride,
    rec_pos,
    rec_force,
):
    """Advance every body ``n_steps`` in place; the arguments are the kernel's."""
    n_bodies, big_n = pos.shape[:2]
    node_ids = np.arange(big_n)
    real = node_ids[None, :] < n_nodes[:, None]  # (P, N)
    count = n_nodes[:, None].astype(np.float64)
    rest_centre = (rest * real[..., None]).sum(axis=1) / count  # (P, 2)
    body_of_edge = np.repeat(np.arange(n_bodies), edges.shape[1]).reshape(edges.shape[:2])
    edge_on = np.arange(edges.shape[1])[None, :] < n_edges[:, None]
    body_of_attr = np.repeat(np.arange(n_bodies), attraction.shape[1]).reshape(attraction.shape[:2])
    attr_on = np.arange(attraction.shape[1])[None, :] < n_attr[:, None]
    if rec_pos.shape[0] > 0:
        rec_pos[0] = np.where(real[..., None], pos, rec_pos[0])
    nodes = np.broadcast_to(node_ids, (n_bodies, big_n))
    clock = np.zeros(n_bodies, dtype=np.int64)
    if wiggle_seeded_phase:
        with np.errstate(over="ignore"):
            start = unit_hash(seeds, WIGGLE_CLOCK_NODE, 2, 0)
        clock = ((start + 1.0) * 0.5 * wiggle_steps).astype(np.int64)
    for s in range(n_steps):
        alive = (status == 0)[:, None] & real  # (P, N)
        step = start_step + s
        last = pos.copy()
        # 1-2. clear forces, force rules
        centre = (pos * real[..., None]).sum(axis=1) / count
        offset = ((centre - rest_centre) * [follow_x, follow_y])[:, None, :]
        moved = np.zeros_like(pos)
        if step < pose.shape[0]:
            moved = np.einsum("pnkd,k->pnd", pose_basis, pose[step])
        force = home[..., None] * (rest + offset + moved - pos)
        force[..., 1] -= gravity * mass * weight
        ticks = (step + clock)[:, None]  # (P, 1)
        knot = ticks // wiggle_steps
        blend = smoothstep((ticks - knot * wiggle_steps) / wiggle_steps)
        seed = seeds[:, None]
        for axis in (0, 1):
            with np.errstate(over="ignore"):  # uint64 arithmetic wraps by design
                lo = unit_hash(seed, nodes, axis, knot)
                hi = unit_hash(seed, nodes, axis, knot + 1)
            force[..., axis] += np.where(wiggle != 0.0, wiggle * (lo + (hi - lo) * blend), 0.0)
        if external.shape[0] > 0:
            force += external[s if external.shape[0] > 1 else 0]
        i, j = attraction[..., 0], attraction[..., 1]
        d = np.take_along_axis(pos, j[..., None], 1) - np.take_along_axis(pos, i[..., None], 1)
        dist = np.sqrt((d**2).sum(-1)) + EDGE_EPSILON
        mag = attr_strength * np.minimum(1.0, dist / ATTRACTION_SOFTNESS) / dist
        mag = np.where(attr_on & (dist < attr_reach), mag, 0.0)
        _scatter(force, body_of_attr, i, mag[..., None] * d)
        if step < drive.shape[0]:
            for p in np.flatnonzero(n_act > 0):
                actuate.py_func(p, n_nodes[p], step, step * dt, pos, force[p], n_edges, edges,
                                n_act, act_node, act_kind, act_channels, act_strength,
                                act_custom, drive, phase)  # fmt: skip
        # 3. springs
        i, j = edges[..., 0], edges[..., 1]
        d = np.take_along_axis(pos, j[..., None], 1) - np.take_along_axis(pos, i[..., None], 1)
        length = np.sqrt((d**2).sum(-1)) + EDGE_EPSILON
        f = np.where(edge_on, strength * (length - rest_length) / length, 0.0)[..., None] * d
        _scatter(force, body_of_edge, i, f)
        _scatter(force, body_of_edge, j, -f)
        force = np.where(alive[..., None], force, 0.0)
        if rec_force.shape[0] > 0 and s % record_stride == 0:
            rec_force[s // record_stride] = np.where(alive[..., None], force, 0.0)
        # 4. integrate
        new_vel = vel + force * (dt / mass)[..., None]
        new_pos = pos + new_vel * dt
        # 5. easing
        d = np.take_along_axis(new_pos, j[..., None], 1) - np.take_along_axis(
            new_pos, i[..., None], 1
        )
        length = np.sqrt((d**2).sum(-1)) + EDGE_EPSILON
        c = np.where(edge_on & (easing > 0), 0.5 * easing * (length - rest_length) / length, 0.0)
        delta = np.zeros_like(new_pos)
        _scatter(delta, body_of_edge, i, c[..., None] * d)
        _scatter(delta, body_of_edge, j, -c[..., None] * d)
        new_pos = new_pos + delta
        # 6. drag, floor
        new_vel = new_vel * (1.0 - drag)[:, None, None]
        if floor:
            ground = floor_y + radius
            below = new_pos[..., 1] < ground
            new_pos[..., 1] = np.where(below, ground, new_pos[..., 1])
            down = below & (new_vel[..., 1] < 0.0)
            new_vel[..., 1] = np.where(down, -restitution * new_vel[..., 1], new_vel[..., 1])
            new_vel[..., 0] = np.where(below, new_vel[..., 0] * (1.0 - friction), new_vel[..., 0])
        pos[:] = np.where(alive[..., None], new_pos, pos)
        vel[:] = np.where(alive[..., None], new_vel, vel)
        # health check
        with np.errstate(invalid="ignore", over="ignore"):
            speed2 = (vel**2).sum(-1)
            finite = np.isfinite(pos).all(-1) & np.isfinite(speed2)
            non_finite = (~finite & alive).any(axis=1)
            runaway = ((speed2 > max_speed**2) & alive).any(axis=1) & ~non_finite
        newly = (status == 0) & (non_finite | runaway)
        status[newly & non_finite] = 1
        status[newly & runaway] = 2
        failed_step[newly] = step
        pos[newly] = last[newly]
        vel[newly] = 0.0
        if rec_pos.shape[0] > 0 and (s + 1) % record_stride == 0:
            rec_pos[(s + 1) // record_stride] = np.where(real[..., None], pos, 0.0)
    if rec_pos.shape[0] > 0:
        frozen = status != 0
        first = (failed_step - start_step) // record_stride + 1
        for r in range(rec_pos.shape[0]):
            late = frozen & (r >= first)
            rec_pos[r][late] = np.where(real[late][..., None], pos[late], 0.0)
