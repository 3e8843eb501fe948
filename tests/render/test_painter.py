"""Drawing frames: body colours, floor, overlay, caption."""

from __future__ import annotations

import numpy as np
import pytest

from render_helpers import PALETTE, RESPONDER_NODES, make_dancer
from sinews.render import FramePainter, Overlay, RasterCanvas, RenderError, Style, make_painter
from sinews.render.painter import frame_index, has_floor
from sinews.trajectory import Trajectory


def draw(painter: FramePainter, frame: int) -> np.ndarray:
    canvas = RasterCanvas(painter.view.width, painter.view.height)
    painter.draw(canvas, frame)
    return canvas.to_array().astype(int)


def test_every_node_shows_its_colour_at_its_position(dancer: Trajectory) -> None:
    painter = make_painter(dancer, 320)
    rgb = draw(painter, 7)
    assert rgb.std() > 10  # not blank
    centres = np.round(painter.view.to_px(dancer.positions[7]) - 0.5).astype(int)
    for (x, y), color in zip(centres, PALETTE.astype(int), strict=True):
        assert np.abs(rgb[y, x] - color).max() <= 3


def test_default_colours_are_distinct_and_radii_have_a_minimum() -> None:
    traj = make_dancer(colors=False, extras=False)
    painter = make_painter(traj, 64, style=Style(default_radius=1e-4))
    rgb = draw(painter, 0)
    centres = np.round(painter.view.to_px(traj.positions[0]) - 0.5).astype(int)
    colours = {tuple(rgb[y, x]) for x, y in centres}
    assert len(colours) >= 10  # visible though tiny, and in many colours


def test_floor_is_drawn_only_under_standing_bodies(dancer: Trajectory) -> None:
    assert has_floor(dancer, Style())
    sunk = Trajectory(
        dancer.positions - np.array([0.0, 1.0], dtype=np.float32),
        dancer.fps,
        dancer.edges,
        dancer.node_names,
    )
    assert not has_floor(sunk, Style())
    assert has_floor(sunk, Style(floor=True))
    painter = make_painter(dancer, 200)
    rgb = draw(painter, 0)
    floor_row = round(painter.view.y_px(0.0))
    assert tuple(rgb[floor_row + 3, 2]) == Style().ground_color


def test_overlay_draws_labels_arrows_and_rings(dancer: Trajectory) -> None:
    plain = draw(make_painter(dancer, 320), 0)
    labels = draw(make_painter(dancer, 320, overlay=Overlay(forces=False)), 0)
    arrows = draw(make_painter(dancer, 320, overlay=Overlay(labels=False)), 0)
    rings_only = Overlay(labels=False, forces=False, responder_nodes=RESPONDER_NODES)
    ringed = draw(make_painter(dancer, 320, overlay=rings_only), 0)
    assert (labels != plain).any(axis=2).sum() > 300
    arrow_red = np.array(Overlay().arrow_color)
    assert (np.abs(arrows - arrow_red).max(axis=2) < 8).sum() > 100
    assert (np.abs(plain - arrow_red).max(axis=2) < 8).sum() == 0
    ring = np.array(Overlay().ring_color)
    assert (np.abs(ringed - ring).max(axis=2) < 8).sum() > 20  # frame 0: l_hand fires
    quiet = draw(make_painter(dancer, 320, overlay=rings_only), 1)
    assert (np.abs(quiet - ring).max(axis=2) < 8).sum() == 0  # frame 1: nobody fires


def test_responder_mapping_must_match_triggers(dancer: Trajectory) -> None:
    with pytest.raises(RenderError, match="responder"):
        make_painter(dancer, 64, overlay=Overlay(responder_nodes=[0]))
    with pytest.raises(RenderError, match="responder"):
        make_painter(dancer, 64, overlay=Overlay(responder_nodes=[0, 1, 99]))


def test_caption_is_formatted_per_frame(dancer: Trajectory) -> None:
    a = draw(make_painter(dancer, 200, caption="t = {time:.2f} s"), 3)
    b = draw(make_painter(dancer, 200, caption="t = {time:.2f} s"), 3)
    c = draw(make_painter(dancer, 200), 3)
    assert (a == b).all() and (a != c).any()
    with pytest.raises(RenderError, match="caption"):
        make_painter(dancer, 64, caption="{speed}")


def test_failed_runs_with_non_finite_nodes_still_draw() -> None:
    traj = make_dancer()
    positions = traj.positions.copy()
    positions[10:, 3] = np.nan
    positions[12:, 4] = 1e30
    broken = Trajectory(positions, traj.fps, traj.edges, traj.node_names, failed=True)
    rgb = draw(make_painter(broken, 100, overlay=True), 15)
    assert rgb.std() > 5


def test_frame_index_defaults_to_the_middle(dancer: Trajectory) -> None:
    assert frame_index(dancer, None) == 15
    assert frame_index(dancer, -1) == 29
    with pytest.raises(RenderError, match="out of range"):
        frame_index(dancer, 30)


def test_onion_skin_puts_the_newest_frame_on_top(dancer: Trajectory) -> None:
    painter = make_painter(dancer, 320)
    canvas = RasterCanvas(320, 320)
    painter.draw(canvas, [0, 8, 15])
    rgb = canvas.to_array().astype(int)
    hand = dancer.node_names.index("l_hand")
    for frame, exact in ((15, True), (0, False)):
        x, y = np.round(painter.view.to_px(dancer.positions[frame, hand]) - 0.5).astype(int)
        matches = np.abs(rgb[y, x] - PALETTE[hand].astype(int)).max() <= 3
        assert matches == exact


def test_draw_accepts_numpy_and_negative_indices(dancer: Trajectory) -> None:
    painter = make_painter(dancer, 64)
    canvas = RasterCanvas(64, 64)
    painter.draw(canvas, np.int64(-1))
    last = canvas.to_array()
    painter.draw(canvas, [29])
    assert (canvas.to_array() == last).all()
    with pytest.raises(RenderError):
        painter.draw(canvas, [])
    with pytest.raises(RenderError, match="out of range"):
        painter.draw(canvas, 30)
