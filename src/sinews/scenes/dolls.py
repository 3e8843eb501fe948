"""Ragdolls for Falling for You: developed dancer bodies, tuned to drift and fall slowly.

A doll is a random `DancerGenome` developed into the 17-node tensegrity
humanoid (without its dance responders), with a little jitter for life. Its
weight (the gravity multiplier) is low and varies from doll to doll, so
dolls fall slowly at different speeds; a baby is the same made smaller,
keeping every natural frequency (masses, springs and home pull scale
together).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from sinews.dancers import DancerGenome, develop
from sinews.springmass import Body

__all__ = ["DOLL_WEIGHT", "HANDS", "doll"]

HANDS = ("l_hand", "r_hand")
"""The nodes that reach for, and hold, other dolls' hands."""
DOLL_WEIGHT = 0.06
"""Typical gravity multiplier of a doll: with the scene's drag it falls about 0.3 m/s."""
_HOME = 0.5
"""Fraction of a dancer's home pull a doll keeps: it holds its shape but gives a little."""


def doll(rng: np.random.Generator, *, scale: float = 1.0) -> Body:
    """A ragdoll (``scale`` < 1 for a baby), centred on x = 0, feet near y = 0.

    Args:
        rng: its genome and weight.
        scale: length factor; masses, springs and home pull scale by its
            square (a 2-D body), so it moves as briskly as a grown doll.
    """
    genome = DancerGenome.random(rng).replace(
        jitter=rng.uniform(0.15, 0.4), arm_spread=rng.uniform(0.25, 0.6)
    )
    body = develop(genome, min_pull=False).without_actuators()
    area = scale**2
    centre = body.rest.mean(axis=0)
    return dataclasses.replace(
        body,
        rest=centre + (body.rest - centre) * scale,
        radius=body.radius * scale,
        rest_length=body.rest_length * scale,
        mass=body.mass * area,
        strength=body.strength * area,
        home=body.home * area * _HOME,
        wiggle=body.wiggle * area,
        weight=np.full(body.n_nodes, DOLL_WEIGHT * rng.uniform(0.7, 1.4)),
    )
