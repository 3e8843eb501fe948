"""3D figures' replays as a binary pack for the figure page's three.js drawer (solid.js).

The page draws shapes, not physics: `sinews.figures.geoms.Shapes` says what
each shape is and where it is in every frame. Positions travel as int16
millimetres (like dancers' nodes), orientations as int16 quaternions scaled
by 32767 (an angle error under 0.01°), about 14 bytes per shape per frame:
a 31-DOF humanoid over 5 s at 30 frames/s is about 40 kB.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from sinews.figures.geoms import Shapes
from sinews.studio.pack import MILLIMETRES, encode_pack, millimetres

__all__ = ["QUATERNION_SCALE", "encode_shapes"]

QUATERNION_SCALE = 32767
"""Units per 1.0 of an int16 quaternion component (the header's ``quaternion_scale``)."""


def encode_shapes(shapes: Sequence[Shapes], fps: float, **header: object) -> bytes:
    """One pack of P individuals' ``shapes`` (one model, T frames each) played at ``fps``.

    Header: ``header``'s fields and ``fps``, ``kinds`` (G names), ``sizes`` (G × 3 m),
    ``colours`` (G × 4), ``scale`` (m per position unit), ``quaternion_scale``.
    Arrays: ``positions`` (P, T, G, 3) int16 mm, ``quaternions`` (P, T, G, 4) int16
    (w, x, y, z).
    """
    first = shapes[0]
    together = np.stack([s.quaternions for s in shapes])
    unit = np.linalg.norm(together, axis=-1, keepdims=True)
    quaternions = np.rint(together / np.maximum(unit, 1e-9) * QUATERNION_SCALE)
    return encode_pack(
        {
            **header,
            "fps": float(fps),
            "kinds": list(first.kinds),
            "sizes": np.round(first.sizes.astype(float), 5).tolist(),
            "colours": np.round(first.colours.astype(float), 3).tolist(),
            "scale": MILLIMETRES,
            "quaternion_scale": QUATERNION_SCALE,
        },
        {
            "positions": np.stack([millimetres(s.positions) for s in shapes]),
            "quaternions": quaternions.astype(np.int16),
        },
    )
