"""World metres → pixels."""

from __future__ import annotations

import numpy as np
import pytest

from sinews.render import RenderError, View, world_bounds


def test_world_bounds_include_radii_and_skip_non_finite() -> None:
    positions = np.array([[[0.0, 0.0], [1.0, 2.0]], [[np.nan, 5.0], [3.0, -1.0]]])
    assert world_bounds(positions, [0.1, 0.2]) == pytest.approx((-0.1, -1.2, 3.2, 2.2))
    assert world_bounds(np.full((2, 3, 2), np.inf)) is None


def test_fit_keeps_aspect_flips_y_and_leaves_a_margin() -> None:
    view = View.fit((0.0, 0.0, 1.0, 2.0), (400, 200), margin=0.1)
    corners = view.to_px([[0.0, 0.0], [1.0, 2.0]])
    # Height limits: 2 m into 200 - 2*20 px.
    assert view.scale == pytest.approx(80.0)
    assert corners[0, 1] == pytest.approx(180.0) and corners[1, 1] == pytest.approx(20.0)
    # Centred horizontally.
    assert corners[:, 0].mean() == pytest.approx(200.0)
    assert view.y_px(0.0) == pytest.approx(180.0)


def test_fixed_scale_and_bottom_alignment() -> None:
    view = View.fit((0.0, 0.5, 1.0, 1.0), (100, 100), margin=0.0, scale=50.0, align="bottom")
    assert view.scale == 50.0
    assert view.y_px(0.5) == pytest.approx(100.0)
    x0, y0, x1, y1 = view.box
    assert (x1 - x0, y1 - y0) == pytest.approx((2.0, 2.0))


def test_degenerate_and_missing_boxes_still_fit() -> None:
    point = View.fit((1.0, 1.0, 1.0, 1.0), (100, 100))
    assert point.to_px([1.0, 1.0]) == pytest.approx([50.0, 50.0])
    assert np.isfinite(View.fit(None, (100, 100)).scale)


def test_bad_sizes_and_boxes_are_errors() -> None:
    with pytest.raises(RenderError):
        View.fit((0, 0, 1, 1), (0, 100))
    with pytest.raises(RenderError):
        View.fit((0, 0, float("nan"), 1), (100, 100))
