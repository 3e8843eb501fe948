"""A 3D figure's replay as a binary pack for the page's three.js view (``static/js/view3d.js``).

The page draws shapes, not physics: `sinews.figures.geoms.Shapes` says what
each shape is and where it is in every frame. Positions travel as int16
millimetres (like dancers' nodes), orientations as int16 quaternions scaled
by 32767 (an angle error under 0.01°), about 14 bytes per shape per frame:
a 31-DOF humanoid over 5 s at 30 frames/s is about 40 kB.
"""

from __future__ import annotations

import numpy as np

from sinews.figures.geoms import Shapes
from sinews.studio.pack import MILLIMETRES, encode_pack, millimetres

__all__ = ["QUATERNION_SCALE", "encode_shapes"]

QUATERNION_SCALE = 32767
"""Units per 1.0 of an int16 quaternion component (the header's ``quaternion_scale``)."""


def encode_shapes(shapes: Shapes, fps: float, **header: object) -> bytes:
    """One pack of ``shapes`` played at ``fps`` with further ``header`` fields for the page.

    Header: ``fps``, ``kinds`` (G names), ``sizes`` (G × 3 m), ``colours`` (G × 4),
    ``scale`` (m per position unit), ``quaternion_scale``. Arrays: ``positions``
    (T, G, 3) int16 mm, ``quaternions`` (T, G, 4) int16 (w, x, y, z).
    """
    unit = np.linalg.norm(shapes.quaternions, axis=-1, keepdims=True)
    quaternions = np.rint(shapes.quaternions / np.maximum(unit, 1e-9) * QUATERNION_SCALE)
    return encode_pack(
        {
            **header,
            "fps": float(fps),
            "kinds": list(shapes.kinds),
            "sizes": np.round(shapes.sizes.astype(float), 5).tolist(),
            "colours": np.round(shapes.colours.astype(float), 3).tolist(),
            "scale": MILLIMETRES,
            "quaternion_scale": QUATERNION_SCALE,
        },
        {
            "positions": millimetres(shapes.positions),
            "quaternions": quaternions.astype(np.int16),
        },
    )
