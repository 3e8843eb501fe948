"""What the browser draws of a 3D run: every geom and the floor's marks, posed frame by frame."""

from __future__ import annotations

import numpy as np
import pytest

from sinews.figures.geoms import SHAPE_KINDS, shapes_of
from sinews.figures.tasks3d import humanoid3d_touch, luxo3d_hop
from sinews.studio.shapes_pack import QUATERNION_SCALE, encode_shapes
from studio_helpers import decode_pack

pytest.importorskip("mujoco")


def test_lamp_shapes_follow_the_root_and_the_x_stays_put() -> None:
    model = luxo3d_hop((1.2, -0.8)).figure.model()
    frames = np.tile(model.qpos0, (3, 1))
    frames[1, 0] += 0.5  # the free root slides 0.5 m along x
    frames[2, 3:7] = [np.cos(np.pi / 4), 0, 0, np.sin(np.pi / 4)]  # and turns 90 degrees
    shapes = shapes_of(model, frames)
    assert set(shapes.kinds) <= set(SHAPE_KINDS) and shapes.kinds[0] == "plane"
    assert shapes.positions.shape == (3, len(shapes.kinds), 3)
    np.testing.assert_allclose(np.linalg.norm(shapes.quaternions, axis=-1), 1, atol=1e-6)
    # the marks (world sites) sit at the X whatever the lamp does
    marks = [g for g, kind in enumerate(shapes.kinds) if kind == "box"]
    assert len(marks) == 2
    np.testing.assert_allclose(shapes.positions[:, marks, :2], [[[1.2, -0.8]] * 2] * 3, atol=1e-6)
    # the lamp's base moved 0.5 m in frame 1
    base = shapes.kinds.index("cylinder")
    np.testing.assert_allclose(shapes.positions[1, base] - shapes.positions[0, base],
                               [0.5, 0, 0], atol=1e-6)  # fmt: skip
    assert not np.allclose(shapes.quaternions[2, base], shapes.quaternions[0, base])


def test_humanoid_pack_round_trips_within_a_millimetre() -> None:
    model = humanoid3d_touch().figure.model()
    frames = np.tile(model.qpos0, (5, 1))
    shapes = shapes_of(model, frames)
    frames[:, 2] -= 0.3  # a second individual, crouched 0.3 m lower
    lower = shapes_of(model, frames)
    header, arrays = decode_pack(encode_shapes([shapes, lower], 30.0, title="touch"))
    assert header["title"] == "touch" and header["fps"] == 30.0
    assert header["kinds"] == list(shapes.kinds) and len(header["sizes"]) == len(shapes.kinds)
    assert arrays["positions"].shape == (2, 5, len(shapes.kinds), 3)
    metres = arrays["positions"] * header["scale"]
    np.testing.assert_allclose(metres[0], shapes.positions, atol=6e-4)
    np.testing.assert_allclose(metres[1], lower.positions, atol=6e-4)
    quaternions = arrays["quaternions"] / QUATERNION_SCALE
    np.testing.assert_allclose(quaternions[1], lower.quaternions, atol=1e-4)


def test_bad_recordings_are_refused() -> None:
    model = luxo3d_hop().figure.model()
    with pytest.raises(ValueError, match="qpos must be"):
        shapes_of(model, np.zeros((2, model.nq + 1)))
    frames = np.tile(model.qpos0, (2, 1))
    frames[1, 0] = np.nan
    with pytest.raises(ValueError, match="NaN"):
        shapes_of(model, frames)
