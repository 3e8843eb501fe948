"""The numba frame loop: one parallel kernel over bodies, each body a whole episode.

Per step (seed 000, "Animating tensegrity objects"):
  1. clear forces;
  2. force rules: gravity x weight, home (toward the rest pose, optionally
     following the centroid and moved by the pose signals), wiggle, attraction, actuators, external;
  3. springs: each edge pushes/pulls its ends by strength x (length - ideal);
  4. integrate v += F/m dt, x += v dt;
  5. easing: move edge ends toward the ideal length by ``easing`` of the error;
  6. drag: v *= 1 - drag;
then the optional floor, and the health check (NaN/inf or runaway speed
freezes the body at its last good pose and records why).
`sinews.springmass.reference` is the same maths in plain numpy.
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange

from sinews.springmass.actuators import ActuatorKind, actuator_force
from sinews.springmass.noise import smoothstep, unit_hash

__all__ = [
    "ATTRACTION_SOFTNESS",
    "EDGE_EPSILON",
    "WIGGLE_CLOCK_NODE",
    "actuate",
    "simulate_kernel",
]

EDGE_EPSILON = 1e-9
"""Added to every edge length so a collapsed edge never divides by zero."""

ATTRACTION_SOFTNESS = 0.05
"""Metres under which an attraction fades linearly to zero (no jitter at contact)."""

WIGGLE_CLOCK_NODE = 65535
"""Node number hashed (axis 2, knot 0) with a body's seed for its wiggle clock's start."""

_PULSE = int(ActuatorKind.PULSE)
_hash = njit(cache=True, inline="always")(unit_hash)
_smooth = njit(cache=True, inline="always")(smoothstep)


@njit(cache=True)
def actuate(
    p,
    n,
    step,
    t,
    pos,
    force,
    n_edges,
    edges,
    n_act,
    act_node,
    act_kind,
    act_channels,
    act_strength,
    act_custom,
    drive,
    phase,
):
    """Add body ``p``'s actuator forces at ``step`` into ``force`` (N, 2)."""
    cx = 0.0
    cy = 0.0
    for i in range(n):
        cx += pos[p, i, 0]
        cy += pos[p, i, 1]
    cx /= n
    cy /= n
    for r in range(n_act[p]):
        level = 0.0
        for c in range(act_channels[p, r, 0], act_channels[p, r, 1] + 1):
            level = max(level, drive[step, c])
        if level <= 0.0:
            continue
        i = act_node[p, r]
        if act_kind[p, r] == _PULSE:
            mag = act_strength[p, r] * level * (1.0 if act_custom[p, r] >= 0.5 else -1.0)
            for e in range(n_edges[p]):
                if edges[p, e, 0] == i:
                    other = edges[p, e, 1]
                elif edges[p, e, 1] == i:
                    other = edges[p, e, 0]
                else:
                    continue
                dx = pos[p, other, 0] - pos[p, i, 0]
                dy = pos[p, other, 1] - pos[p, i, 1]
                length = np.sqrt(dx * dx + dy * dy) + EDGE_EPSILON
                force[other, 0] += mag * dx / length
                force[other, 1] += mag * dy / length
                force[i, 0] -= mag * dx / length
                force[i, 1] -= mag * dy / length
        else:
            fx, fy = actuator_force(
                act_kind[p, r],
                level,
                act_strength[p, r],
                act_custom[p, r],
                pos[p, i, 0] - cx,
                pos[p, i, 1] - cy,
                t,
                phase[step],
            )
            force[i, 0] += fx
            force[i, 1] += fy


@njit(cache=True, parallel=True, fastmath=False)
def simulate_kernel(*args):
    """Advance every body ``n_steps`` in place; fill the recordings (threads over bodies).

    Args (``*args``: `_simulate_body`'s arguments after ``p``, in its order):
        pos, vel: (P, N, 2) float64, updated in place.
        status, failed_step: (P,) int8 and int64, updated in place.
        drive: (D, C) actuator drive table, row = global step (none after row D - 1).
        phase: (D,) phase signal in [0, 1) for SWAY actuators.
        pose_basis: (P, N, K, 2) home-target metres per unit of each pose signal.
        pose: (Q, K) pose signals, row = global step (none after row Q - 1).
        external: (S, P, N, 2) caller forces; S = 0 none, 1 constant, n_steps per step.
        rec_pos: (R, P, N, 2) float32 with R = n_steps // record_stride + 1, or R = 0.
        rec_force: like rec_pos (net force in the step after each record), or R = 0.
        Other arrays: as in `BodyBatch`; scalars as in `EngineParams`.
    """
    for p in prange(args[0].shape[0]):
        _simulate_body(p, *args)


@njit(cache=True, fastmath=False)
def simulate_serial(*args):
    """`simulate_kernel` on one thread, the same arithmetic body by body (bit for bit): for
    small batches, where threads buy little and the parallel kernel's compile time is most
    of a first start (measured 10 s against 19 s on an empty cache)."""
    for p in range(args[0].shape[0]):
        _simulate_body(p, *args)


@njit(cache=True, fastmath=False)
def _simulate_body(
    p,
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
    """Body ``p`` of `simulate_kernel`: ``n_steps`` steps of the six-step frame loop."""
    big_n = pos.shape[1]
    n_ext = external.shape[0]
    n_drive = drive.shape[0]
    n_pose = pose.shape[0]
    n_signals = pose.shape[1]
    n_rec = rec_pos.shape[0]
    keep_forces = rec_force.shape[0] > 0
    n = n_nodes[p]
    force = np.zeros((big_n, 2))
    delta = np.zeros((big_n, 2))
    last = np.empty((big_n, 2))
    rest_cx = 0.0
    rest_cy = 0.0
    for i in range(n):
        rest_cx += rest[p, i, 0]
        rest_cy += rest[p, i, 1]
    rest_cx /= n
    rest_cy /= n
    clock = 0
    if wiggle_seeded_phase:
        clock = int((_hash(seeds[p], WIGGLE_CLOCK_NODE, 2, 0) + 1.0) * 0.5 * wiggle_steps)
    if n_rec > 0:
        for i in range(n):
            rec_pos[0, p, i, 0] = pos[p, i, 0]
            rec_pos[0, p, i, 1] = pos[p, i, 1]
    for s in range(n_steps):
        if status[p] != 0:
            break
        step = start_step + s
        # 1. clear forces (and remember the pose to fall back to)
        for i in range(n):
            force[i, 0] = 0.0
            force[i, 1] = 0.0
            last[i, 0] = pos[p, i, 0]
            last[i, 1] = pos[p, i, 1]
        # 2. force rules
        off_x = 0.0
        off_y = 0.0
        if follow_x != 0.0 or follow_y != 0.0:
            for i in range(n):
                off_x += pos[p, i, 0]
                off_y += pos[p, i, 1]
            off_x = follow_x * (off_x / n - rest_cx)
            off_y = follow_y * (off_y / n - rest_cy)
        knot = (step + clock) // wiggle_steps
        blend = _smooth((step + clock - knot * wiggle_steps) / wiggle_steps)
        seed = seeds[p]
        moved = step < n_pose
        for i in range(n):
            gx = 0.0
            gy = 0.0
            if moved:
                for k in range(n_signals):
                    gx += pose_basis[p, i, k, 0] * pose[step, k]
                    gy += pose_basis[p, i, k, 1] * pose[step, k]
            fx = home[p, i] * (rest[p, i, 0] + off_x + gx - pos[p, i, 0])
            fy = home[p, i] * (rest[p, i, 1] + off_y + gy - pos[p, i, 1])
            fy -= gravity * mass[p, i] * weight[p, i]
            amp = wiggle[p, i]
            if amp != 0.0:
                a0 = _hash(seed, i, 0, knot)
                a1 = _hash(seed, i, 0, knot + 1)
                b0 = _hash(seed, i, 1, knot)
                b1 = _hash(seed, i, 1, knot + 1)
                fx += amp * (a0 + (a1 - a0) * blend)
                fy += amp * (b0 + (b1 - b0) * blend)
            if n_ext > 0:
                row = s if n_ext > 1 else 0
                fx += external[row, p, i, 0]
                fy += external[row, p, i, 1]
            force[i, 0] += fx
            force[i, 1] += fy
        for a in range(n_attr[p]):
            i = attraction[p, a, 0]
            j = attraction[p, a, 1]
            dx = pos[p, j, 0] - pos[p, i, 0]
            dy = pos[p, j, 1] - pos[p, i, 1]
            dist = np.sqrt(dx * dx + dy * dy) + EDGE_EPSILON
            if dist < attr_reach[p, a]:
                mag = attr_strength[p, a] * min(1.0, dist / ATTRACTION_SOFTNESS) / dist
                force[i, 0] += mag * dx
                force[i, 1] += mag * dy
        if n_act[p] > 0 and step < n_drive:
            actuate(
                p,
                n,
                step,
                step * dt,
                pos,
                force,
                n_edges,
                edges,
                n_act,
                act_node,
                act_kind,
                act_channels,
                act_strength,
                act_custom,
                drive,
                phase,
            )
        # 3. springs
        for e in range(n_edges[p]):
            i = edges[p, e, 0]
            j = edges[p, e, 1]
            dx = pos[p, j, 0] - pos[p, i, 0]
            dy = pos[p, j, 1] - pos[p, i, 1]
            length = np.sqrt(dx * dx + dy * dy) + EDGE_EPSILON
            f = strength[p, e] * (length - rest_length[p, e]) / length
            force[i, 0] += f * dx
            force[i, 1] += f * dy
            force[j, 0] -= f * dx
            force[j, 1] -= f * dy
        if keep_forces and s % record_stride == 0:
            r = s // record_stride
            for i in range(n):
                rec_force[r, p, i, 0] = force[i, 0]
                rec_force[r, p, i, 1] = force[i, 1]
        # 4. integrate
        for i in range(n):
            inv_m = dt / mass[p, i]
            vel[p, i, 0] += force[i, 0] * inv_m
            vel[p, i, 1] += force[i, 1] * inv_m
            pos[p, i, 0] += vel[p, i, 0] * dt
            pos[p, i, 1] += vel[p, i, 1] * dt
        # 5. easing (all corrections from the same pose, then applied)
        eased = False
        for e in range(n_edges[p]):
            ease = easing[p, e]
            if ease > 0.0:
                if not eased:
                    for i in range(n):
                        delta[i, 0] = 0.0
                        delta[i, 1] = 0.0
                    eased = True
                i = edges[p, e, 0]
                j = edges[p, e, 1]
                dx = pos[p, j, 0] - pos[p, i, 0]
                dy = pos[p, j, 1] - pos[p, i, 1]
                length = np.sqrt(dx * dx + dy * dy) + EDGE_EPSILON
                c = 0.5 * ease * (length - rest_length[p, e]) / length
                delta[i, 0] += c * dx
                delta[i, 1] += c * dy
                delta[j, 0] -= c * dx
                delta[j, 1] -= c * dy
        if eased:
            for i in range(n):
                pos[p, i, 0] += delta[i, 0]
                pos[p, i, 1] += delta[i, 1]
        # 6. drag, then the floor
        keep = 1.0 - drag[p]
        limit = max_speed * max_speed
        bad = 0
        for i in range(n):
            vel[p, i, 0] *= keep
            vel[p, i, 1] *= keep
            if floor:
                ground = floor_y + radius[p, i]
                if pos[p, i, 1] < ground:
                    pos[p, i, 1] = ground
                    if vel[p, i, 1] < 0.0:
                        vel[p, i, 1] = -restitution * vel[p, i, 1]
                    vel[p, i, 0] *= 1.0 - friction
            speed2 = vel[p, i, 0] * vel[p, i, 0] + vel[p, i, 1] * vel[p, i, 1]
            if not (
                np.isfinite(pos[p, i, 0]) and np.isfinite(pos[p, i, 1]) and np.isfinite(speed2)
            ):
                bad = 1
            elif speed2 > limit and bad == 0:
                bad = 2
        if bad != 0:
            status[p] = bad
            failed_step[p] = step
            for i in range(n):
                pos[p, i, 0] = last[i, 0]
                pos[p, i, 1] = last[i, 1]
                vel[p, i, 0] = 0.0
                vel[p, i, 1] = 0.0
        if n_rec > 0 and (s + 1) % record_stride == 0:
            r = (s + 1) // record_stride
            for i in range(n):
                rec_pos[r, p, i, 0] = pos[p, i, 0]
                rec_pos[r, p, i, 1] = pos[p, i, 1]
    # a frozen body holds its last good pose in the frames it did not live
    if n_rec > 0 and status[p] != 0:
        first = (failed_step[p] - start_step) // record_stride + 1
        for r in range(max(first, 0), n_rec):
            for i in range(n):
                rec_pos[r, p, i, 0] = pos[p, i, 0]
                rec_pos[r, p, i, 1] = pos[p, i, 1]
