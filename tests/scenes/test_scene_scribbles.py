"""Scribbles: curves become bones, a seeded rule adds tendons, and the drawing comes alive."""

from __future__ import annotations

import numpy as np
import pytest

from sinews.errors import SinewsError
from sinews.scenes import SceneInput, Scribbles
from sinews.scenes.scribble import GAITS, Tendons, resample
from sinews.scenes.scripts import preset_curves

WAVE = np.stack([np.linspace(-1.5, 1.5, 60), 0.3 * np.sin(np.linspace(0, 3 * np.pi, 60))], axis=1)


def shape_and_place(scene: Scribbles, scribble_id: int) -> tuple[np.ndarray, np.ndarray]:
    """(n, 2) node positions relative to their centroid, and the centroid."""
    pos = scene.world.positions[scene.scribbles[scribble_id].nodes]
    return pos - pos.mean(axis=0), pos.mean(axis=0)


def test_a_curve_is_resampled_to_evenly_spaced_nodes_from_end_to_end() -> None:
    drawn = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 0.0], [1.0, 2.0]])  # a repeated point
    nodes = resample(drawn, 0.25, 40)
    steps = np.hypot(*np.diff(nodes, axis=0).T)
    assert len(nodes) == 13 and np.allclose(steps, 0.25)
    assert np.allclose(nodes[[0, -1]], drawn[[0, -1]])
    assert len(resample(drawn, 0.01, 20)) == 20  # long curves get wider spacing
    assert len(resample(drawn, 10.0, 20)) == 3
    with pytest.raises(SinewsError, match="a few millimetres"):
        resample([[0.0, 0.0], [0.0, 0.0]], 0.1, 10)


def test_the_tendon_rule_joins_non_adjacent_nodes_and_follows_its_seed() -> None:
    nodes = resample(WAVE, 0.15, 30)
    for seed in range(20):
        tendons = Tendons.generate(nodes, np.random.default_rng(seed))
        i, j = tendons.pairs.T
        assert np.all(j - i >= 2) and i.min() >= 0 and j.max() < len(nodes)
        assert tendons.gait in GAITS
        lengths = [tendons.rest_lengths(t) for t in np.linspace(0.0, 5.0, 40)]
        assert np.all((np.array(lengths) > 0.25 * tendons.relaxed) & (lengths <= tendons.relaxed))
    again = Tendons.generate(nodes, np.random.default_rng(3))
    first = Tendons.generate(nodes, np.random.default_rng(3))
    assert np.array_equal(again.pairs, first.pairs) and again.tempo == first.tempo


def test_a_scribble_moves_like_a_creature() -> None:
    scene = Scribbles(np.random.default_rng(0))
    sid = scene.add_scribble(WAVE)
    shape0, place0 = shape_and_place(scene, sid)
    for _ in range(5 * 60):
        scene.step()
    shape1, place1 = shape_and_place(scene, sid)
    moved = np.hypot(*(place1 - place0))
    changed = np.abs(shape1 - shape0).max()
    assert moved > 0.05 or changed > 0.2
    assert not scene.world.failed


def test_the_same_curve_with_other_tendons_moves_differently() -> None:
    paths = []
    for seed in (1, 2):
        scene = Scribbles(np.random.default_rng(0))
        sid = scene.add_scribble(WAVE, np.random.default_rng(seed))
        paths.append([shape_and_place(scene, sid)[1]])
        for _ in range(6):
            for _ in range(30):
                scene.step()
            paths[-1].append(shape_and_place(scene, sid)[1])
    gap = np.hypot(*(np.array(paths[0]) - np.array(paths[1])).T)
    assert gap[0] == 0.0 and gap.max() > 0.05


def test_several_scribbles_live_at_once_and_tendons_can_be_rerolled() -> None:
    scene = Scribbles(np.random.default_rng(4), slots=3)
    curves = preset_curves(scene.screen)
    frame = scene.step(SceneInput(stroke=tuple(map(tuple, curves[0]))))
    assert [e.kind for e in frame.events] == ["scribble"] and frame.score == 1
    ids = [scene.add_scribble(c) for c in curves[1:]]
    assert sorted(scene.scribbles) == ids  # the oldest (id 0) made room
    sid = ids[-1]
    before = scene.scribbles[sid].tendons.pairs
    on = scene.world.strength[scene.scribbles[sid].springs].copy()
    scene.regenerate_tendons(sid, np.random.default_rng(99))
    after = scene.scribbles[sid].tendons.pairs
    assert not np.array_equal(before, after)
    assert np.all(on > 0) and np.all(scene.world.strength[scene.scribbles[sid].springs] > 0)
    visible = scene.world.edge_visible
    assert visible.sum() == sum(len(s.bones) + len(s.springs) for s in scene.scribbles.values())
    for _ in range(60):
        scene.step()
    assert not scene.world.failed
