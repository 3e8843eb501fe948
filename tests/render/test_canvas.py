"""The Canvas seam: both back ends draw the same primitives."""

from __future__ import annotations

import xml.etree.ElementTree as ET

import numpy as np
import pytest

from sinews.render import Canvas, RasterCanvas, RenderError, SvgCanvas
from sinews.render.canvas import arrow_geometry

SVG_NS = "{http://www.w3.org/2000/svg}"
RED = (220, 20, 20)
WHITE = (255, 255, 255)


def draw_everything(canvas: Canvas) -> None:
    canvas.clear(WHITE)
    canvas.line((5, 5), (60, 40), (0, 0, 0), 3)
    canvas.circle((32, 32), 10, RED, (0, 0, 0), 1)
    canvas.polygon([(2, 60), (20, 60), (10, 50)], (0, 160, 0), None)
    canvas.arrow((40, 60), (60, 50), (0, 0, 200), 2)
    canvas.text((2, 2), "a<b & c", (0, 0, 0), size=10, anchor="lt", halo=WHITE)


@pytest.mark.parametrize("canvas", [RasterCanvas(64, 64), SvgCanvas(64, 64)])
def test_back_ends_follow_the_protocol(canvas: Canvas) -> None:
    assert isinstance(canvas, Canvas)
    assert canvas.size == (64, 64)
    draw_everything(canvas)


def test_raster_fills_circles_and_antialiases_edges() -> None:
    canvas = RasterCanvas(64, 64, supersample=3)
    canvas.clear(WHITE)
    canvas.circle((32, 32), 12, RED)
    rgb = canvas.to_array()
    assert rgb.shape == (64, 64, 3) and rgb.dtype == np.uint8
    assert tuple(rgb[32, 32]) == RED
    assert tuple(rgb[2, 2]) == WHITE
    # Anti-aliasing: the rim has colours between the fill and the background.
    reds = rgb[..., 1]
    assert ((reds > RED[1] + 10) & (reds < 245)).sum() > 20


def test_raster_text_leaves_ink() -> None:
    canvas = RasterCanvas(80, 30)
    canvas.clear(WHITE)
    canvas.text((40, 15), "head", (0, 0, 0), size=12, anchor="mm")
    assert (canvas.to_array() < 128).any()


@pytest.mark.parametrize("canvas", [RasterCanvas(10, 10), SvgCanvas(10, 10)])
def test_unknown_anchor_is_an_error(canvas: Canvas) -> None:
    with pytest.raises(RenderError, match="anchor"):
        canvas.text((0, 0), "x", (0, 0, 0), anchor="xx")


def test_svg_is_well_formed_and_escapes_text() -> None:
    canvas = SvgCanvas(64, 64)
    draw_everything(canvas)
    root = ET.fromstring(canvas.to_string())
    assert root.tag == f"{SVG_NS}svg" and root.get("viewBox") == "0 0 64 64"
    tags = [el.tag.removeprefix(SVG_NS) for el in root]
    assert tags.count("line") == 2  # the line and the arrow's shaft
    assert tags.count("polygon") == 2  # the polygon and the arrow's head
    assert "circle" in tags
    text = root.find(f"{SVG_NS}text")
    assert text is not None and text.text == "a<b & c"


def test_clear_forgets_svg_elements() -> None:
    canvas = SvgCanvas(8, 8)
    canvas.circle((4, 4), 2, RED)
    canvas.clear(WHITE)
    assert "<circle" not in canvas.to_string()


def test_arrow_head_points_at_the_end() -> None:
    shaft_end, (tip, left, right) = arrow_geometry((0, 0), (100, 0), 2)
    assert tip == (100, 0)
    assert 0 < shaft_end[0] < 100 and left[0] == right[0] < 100
    assert left[1] == -right[1] != 0
    # Short arrows keep a head no longer than half of them.
    _, (_, left, _) = arrow_geometry((0, 0), (4, 0), 2)
    assert left[0] >= 2
