"""The scene machinery: one merged body on the dancers' engine, parts switched between steps."""

from __future__ import annotations

import numpy as np
import pytest

from sinews.scenes import SCENE_NAMES, SceneInput, make_scene, player
from sinews.scenes.assembly import Assembly
from sinews.scenes.world import World
from sinews.springmass import Body, EngineParams


def two_bodies() -> World:
    """Two triangles with home pulls, a spare balloon and an inactive link spring."""
    assembly = Assembly()
    tri = Body.build(
        ["a", "b", "c"], [[0.0, 0.0], [1.0, 0.0], [0.5, 1.0]], [[0, 1], [1, 2], [2, 0]],
        mass=[1.0, 2.0, 3.0], home=[5.0, 10.0, 15.0],
    )  # fmt: skip
    left = assembly.add_body("left", tri)
    assembly.add_body("right", tri)
    balloon = assembly.add_node("balloon", (0.0, 9.0), mass=1.0, radius=0.2, color=(200, 0, 0),
                                weight=-2.0, shape="heart", active=False)  # fmt: skip
    assembly.add_spring(left.nodes.start, 3, 0.1, 50.0, 0.2, active=False)
    assembly.add_attraction(0, 3, 5.0, 1.0)
    world = World(assembly.build(drag=0.05), EngineParams(floor=False), seed=1)
    world.positions[3:6] += [3.0, 0.0]
    world.shape[3:6] += [3.0, 0.0]
    assert balloon == 6
    return world


def test_spare_parts_start_off_and_parked_nodes_stay_put() -> None:
    world = two_bodies()
    assert world.node_visible.tolist() == [True] * 6 + [False]
    assert world.edge_visible.tolist() == [True] * 6 + [False]
    assert world.strength[6] == 0.0 and world.easing[6] == 0.0  # the link is off
    assert world.attraction_strength[0] == 0.0
    assert world.layout.body.strength[6] == 50.0  # its "on" value is kept
    before = world.positions[6].copy()
    for _ in range(30):
        world.step(np.zeros((7, 2)))
    assert np.array_equal(world.positions[6], before)  # weightless and still


def test_switching_on_a_link_and_revealing_a_balloon() -> None:
    world = two_bodies()
    world.switch(6, on=True)
    assert world.strength[6] == 50.0 and world.edge_visible[6]
    world.reveal(6, np.array([1.0, 2.0]), np.zeros(2))
    assert world.node_visible[6] and world.weight[6] == -2.0
    world.step(np.zeros((7, 2)))
    assert world.velocities[6, 1] > 0.0  # a balloon rises


def test_home_follows_each_part_and_never_pushes_it() -> None:
    world = two_bodies()
    world.positions[:6] += np.random.default_rng(0).normal(0.0, 0.2, (6, 2))
    world.follow_home([slice(0, 3), slice(3, 6)])
    for part in (slice(0, 3), slice(3, 6)):
        home = world.home[part, None] * (world.rest[part] - world.positions[part])
        assert np.allclose(home.sum(axis=0), 0.0)  # holds the shape, adds no net force


@pytest.mark.parametrize("name", SCENE_NAMES)
def test_same_seed_same_scene_bit_for_bit(name: str) -> None:
    def run() -> tuple[np.ndarray | None, ...]:
        scene = make_scene(name, np.random.default_rng(7))
        script = player(scene, np.random.default_rng(8))
        got = scene.record(4.0, script)
        return (
            got.trajectory.positions,
            got.trajectory.node_visible,
            got.trajectory.edge_visible,
            got.score,
            got.camera,
        )

    first, second = run(), run()
    for a, b in zip(first, second, strict=True):
        assert a is not None and b is not None and np.array_equal(a, b)


@pytest.mark.parametrize("name", SCENE_NAMES)
def test_a_frame_has_what_a_live_view_draws(name: str) -> None:
    scene = make_scene(name, np.random.default_rng(0), record_forces=True)
    frame = scene.step(SceneInput(pointer=(0.0, 1.0), pressed=True))
    n_nodes, n_edges = scene.world.n_nodes, scene.world.layout.body.n_edges
    assert frame.positions.shape == (n_nodes, 2) and frame.positions.dtype == np.float32
    assert frame.node_visible.shape == (n_nodes,) and frame.edge_visible.shape == (n_edges,)
    assert frame.forces is not None and frame.forces.shape == (n_nodes, 2)
    assert frame.step == 1 and frame.time == pytest.approx(1 / 60)
    assert len(frame.camera) == 2
    run = scene.record(0.5)
    traj = run.trajectory
    assert traj.n_frames == 31 and traj.fps == pytest.approx(60.0)
    assert traj.forces is not None and traj.node_shapes is not None
    assert run.camera.shape == (31, 2) and run.score.shape == (31,)
