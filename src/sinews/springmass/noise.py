"""Counter-based noise for the wiggle force: the same numbers in numba and numpy.

A value depends only on (seed, node, axis, knot), never on call order or on
other bodies, so wiggle is deterministic per body whatever the batch.
``unit_hash`` is plain arithmetic on uint64: the numba kernel compiles it for
scalars and the numpy reference calls it on arrays.
"""

from __future__ import annotations

import numpy as np

__all__ = ["smoothstep", "unit_hash"]

_GOLDEN = np.uint64(0x9E3779B97F4A7C15)
_MIX1 = np.uint64(0xBF58476D1CE4E5B9)
_MIX2 = np.uint64(0x94D049BB133111EB)
_AXIS = np.uint64(0xD1B54A32D192ED03)
_S30, _S27, _S31, _S11 = np.uint64(30), np.uint64(27), np.uint64(31), np.uint64(11)
_INV53 = 1.0 / 9007199254740992.0  # 2**-53


def unit_hash(seed, node, axis, knot):  # scalars or arrays
    """A uniform number in [-1, 1) from uint64 ``seed`` and integer ``node, axis, knot``.

    SplitMix64 finaliser over a mix of the inputs; works elementwise on arrays.
    """
    z = (
        seed ^ (np.uint64(node) * _GOLDEN) ^ (np.uint64(axis) * _AXIS) ^ (np.uint64(knot) * _MIX2)
    ) + _GOLDEN
    z = (z ^ (z >> _S30)) * _MIX1
    z = (z ^ (z >> _S27)) * _MIX2
    z = z ^ (z >> _S31)
    return (z >> _S11) * _INV53 * 2.0 - 1.0


def smoothstep(f):  # scalars or arrays
    """Cubic ease 3f² − 2f³ for f in [0, 1]."""
    return f * f * (3.0 - 2.0 * f)
