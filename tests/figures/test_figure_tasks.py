"""Tasks: scenes, terminals and fitness terms, on hand-made motions."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("mujoco")

from sinews.control import HoldPose
from sinews.figures import FigureError, rollout
from sinews.figures.luxo import luxo
from sinews.figures.task import MAIN_GOALS, standing_height
from sinews.figures.tasks import (
    TASKS,
    TERMS,
    TOUCH_HOLD,
    Goal,
    Task,
    TaskMeter,
    humanoid_reach,
    luxo_hop,
    luxo_limbo,
    make_task,
)


@pytest.fixture(scope="module")
def hop() -> Task:
    return luxo_hop(1.5)


def test_the_built_in_tasks_build() -> None:
    for name in TASKS:
        task = make_task(name)
        assert next(iter(task.weights)) in MAIN_GOALS
        assert set(task.weights) <= set(TERMS)
        assert len(task.actuators) == len(task.joints)
        weights, offset = task.input_map()
        assert weights.shape == (task.figure.n_sensors + len(task.music), len(task.terminals))
        assert offset.shape == (len(task.terminals),)
    limbo = luxo_limbo(0.25)
    assert limbo.figure.touch_bodies == ("pole",)
    assert {"fx_pole", "fz_pole"} <= set(limbo.figure.sensor_names)
    assert limbo.weights["touch"] > limbo.weights["head"]
    reach = humanoid_reach("nose")
    assert reach.figure.sites == ("hand_r", "nose")
    assert reach.goal.target == ("x_nose", "z_nose")
    assert luxo_hop(-0.5).goal.target == (-0.5, 0.0)  # on the floor
    assert "gx" in luxo_hop().terminals and "gz" not in luxo_hop().terminals


def test_a_lamp_in_mid_hop_over_the_x_is_not_on_it(hop: Task) -> None:
    """The X is on the floor: at the end one lamp stands on it, one is 13 cm above it."""
    meter = TaskMeter(hop, 2)
    for k in range(11):
        height = [0.0, 0.13 * k / 10]
        sensors = sensors_for(hop, time=[k / 10] * 2, root_x=[1.5, 1.5], root_z=height)
        meter(k / 10, sensors, np.zeros((2, 3)))
    distance = meter.terms()[:, list(hop.weights).index("distance")]
    np.testing.assert_allclose(distance, [0.0, -0.13], atol=1e-12)


@pytest.mark.parametrize(
    ("name", "options"),
    [
        ("luxo-hop", {"target": 0.2}),
        ("luxo-hop", {"target": -2.5}),
        ("luxo-limbo", {"pole_height": 0.0}),
        ("luxo-limbo", {"pole_x": 2.0}),
        ("humanoid-reach", {"target": "ear"}),
        ("luxo-hop", {"bogus": 1}),
        ("walk", {}),
    ],
)
def test_bad_task_options_are_refused(name: str, options: dict[str, object]) -> None:
    with pytest.raises(FigureError):
        make_task(name, **options)


def test_terminals_are_sensors_and_goal_relative_positions(hop: Task) -> None:
    reach = humanoid_reach("nose")
    for task in (hop, reach):
        weights, offset = task.input_map()
        sensors = np.random.default_rng(0).normal(size=(5, task.figure.n_sensors))
        inputs = sensors @ weights + offset
        column = task.figure.sensor_index
        for v, name in enumerate(task.sensors):
            np.testing.assert_array_equal(inputs[:, v], sensors[:, column(name)])
    hop_inputs = sensors_for(hop, root_x=[0.25, 2.0]) @ hop.input_map()[0] + hop.input_map()[1]
    np.testing.assert_allclose(hop_inputs[:, hop.terminals.index("gx")], [1.25, -0.5])
    weights, offset = reach.input_map()
    sensors = np.random.default_rng(1).normal(size=(3, reach.figure.n_sensors))
    gz = (sensors @ weights + offset)[:, reach.terminals.index("gz")]
    column = reach.figure.sensor_index
    np.testing.assert_allclose(gz, sensors[:, column("z_nose")] - sensors[:, column("z_hand_r")])


def sensors_for(task: Task, **columns: list[float]) -> np.ndarray:
    """(P, S) zero sensors with some named columns set."""
    n = len(next(iter(columns.values())))
    sensors = np.zeros((n, task.figure.n_sensors))
    for name, values in columns.items():
        sensors[:, task.figure.sensor_index(name)] = values
    return sensors


def test_terms_of_a_hand_made_motion(hop: Task) -> None:
    """Three lamps over 5 s at 10 observations/s: one arrives at 2 s then wobbles, one never
    moves, one passes the X at 1 s and stops 0.3 m beyond it."""
    meter = TaskMeter(hop, 3)
    targets = np.zeros((3, 3))
    for k in range(51):
        t = k / 10
        x = min(t / 2, 1.0) * 1.5 + (0.01 * (-1) ** k if t > 2 else 0.0)
        sensors = sensors_for(
            hop,
            time=[t, t, t],
            root_x=[x, 0.0, min(t, 1.2) * 1.5],
            root_pitch=[1.2 if 1.0 <= t < 1.5 else 0.0, 0.0, 0.0],  # fallen for 5 observations
            fz_head=[3.0 if k < 10 else 0.0, 0.0, 0.0],  # head down for 10
            q_neck=[0.4, 0.0, 0.0],
        )
        meter(t, sensors, targets)
    terms = dict(zip(hop.weights, meter.terms().T, strict=True))
    assert meter.observations == 51
    np.testing.assert_allclose(terms["distance"], [-0.01, -1.5, -0.3], atol=1e-12)
    np.testing.assert_allclose(terms["early"], [1 - 2.0 / 5.0, 0.0, 0.0])  # passing is not arriving
    moves = 0.01 + 29 * 0.02  # 30 moves after arrival
    np.testing.assert_allclose(terms["still"], [-moves, 0.0, -0.3], atol=1e-12)
    np.testing.assert_allclose(terms["head"], [-10 / 51, 0.0, 0.0])
    np.testing.assert_allclose(terms["fallen"], [-5 / 51, 0.0, 0.0])
    np.testing.assert_allclose(terms["neutral"], [-0.4 / 3, 0.0, 0.0])
    np.testing.assert_allclose(terms["energy"], [0.0, 0.0, 0.0])


def test_a_lamp_on_its_arm_is_down_even_upright_enough(hop: Task) -> None:
    """Scooting on the base's edge and the upper arm (pitch under max_tilt) counts as fallen."""
    meter = TaskMeter(hop, 2)
    for k in range(20):
        on_arm = 5 <= k < 12
        sensors = sensors_for(
            hop,
            time=[k / 10] * 2,
            root_pitch=[-0.9, 0.0],
            fz_arm_upper=[4.0 if on_arm else 0.0, 0.0],
        )
        meter(k / 10, sensors, np.zeros((2, 3)))
    fallen = meter.terms()[:, list(hop.weights).index("fallen")]
    np.testing.assert_allclose(fallen, [-7 / 20, 0.0])


def test_terms_of_a_lamp_at_rest_and_the_observer_changes_nothing(hop: Task) -> None:
    figure = hop.figure
    meter = TaskMeter(hop, 2)
    calls = []

    def observe(t: float, sensors: np.ndarray, targets: np.ndarray) -> None:
        calls.append(t)
        meter(t, sensors, targets)

    hold = HoldPose(figure.neutral)
    seen = rollout(figure, hold, 2, 0.5, observer=observe, record=True)
    unseen = rollout(figure, hold, 2, 0.5, record=True)
    np.testing.assert_array_equal(seen.qpos, unseen.qpos)
    assert len(calls) == 51 and calls[-1] == 0.5
    terms = dict(zip(hop.weights, meter.terms().T, strict=True))
    np.testing.assert_allclose(terms["distance"], -1.5, atol=1e-3)
    for name in ("early", "still", "head", "fallen"):
        np.testing.assert_array_equal(terms[name], 0.0)
    assert (np.abs(terms["neutral"]) < 0.05).all() and (terms["energy"] <= 0).all()


def test_the_limbo_pole_is_felt_only_when_touched() -> None:
    low = luxo_limbo(0.33, pole_x=0.05, target=1.0)  # through the resting lamp's upper arm
    high = luxo_limbo(0.9, target=1.0)
    for task, touched in ((low, True), (high, False)):
        meter = TaskMeter(task, 1)
        rollout(task.figure, HoldPose(task.figure.neutral), 1, 0.3, observer=meter)
        touch = meter.terms()[0, list(task.weights).index("touch")]
        assert (touch < 0) == touched


def test_ducking_is_measured_above_the_bar_until_the_lamp_has_passed_it() -> None:
    """Standing before the 0.25 m bar, folded low before it, standing past it."""
    task = luxo_limbo(0.25, target=1.0)  # the bar at x = 0.5
    meter = TaskMeter(task, 3)
    for k in range(5):
        sensors = sensors_for(task, root_x=[0.1, 0.1, 0.6], z_elbow=[0.3, 0.2, 0.3],
                              z_neck=[0.4, 0.2, 0.4], z_shade_back=[0.35, 0.15, 0.35],
                              z_shade=[0.35, 0.1, 0.35])  # fmt: skip
        meter(k / 10, sensors, np.zeros((3, 3)))
    duck = meter.terms()[:, list(task.weights).index("duck")]
    # the top of the neck's arm is 1.2 cm above its axis: 0.412 m standing, 0.212 folded
    np.testing.assert_allclose(duck, [-0.162, 0.0, 0.0], atol=1e-12)
    behind = luxo_limbo(0.25, target=-1.0)  # the bar at x = -0.5: x = 0.1 is before it
    meter = TaskMeter(behind, 1)
    meter(0.0, sensors_for(behind, root_x=[0.1], z_neck=[0.4]), np.zeros((1, 3)))
    assert meter.terms()[0, list(behind.weights).index("duck")] == pytest.approx(-0.162)


def test_a_standing_lamp_ducks_as_far_as_its_top_is_above_the_bar() -> None:
    """The rest pose in physics: the duck term is the top of its geoms above the bar."""
    top = standing_height(luxo())
    penalties = []
    for height in (top - 0.1, top - 0.01, top):
        task = luxo_limbo(height)
        meter = TaskMeter(task, 1)
        rollout(task.figure, HoldPose(task.figure.neutral), 1, 0.3, observer=meter)
        penalties.append(meter.terms()[0, list(task.weights).index("duck")])
    # held by its servos the lamp sags a few mm below its rest pose's top
    assert penalties[0] - penalties[1] == pytest.approx(-0.09, abs=1e-9)
    assert -0.01 < penalties[1] < -0.001 and penalties[2] == pytest.approx(0.0, abs=1e-12)
    with pytest.raises(FigureError, match="duck"):
        Task(**{**vars(luxo_hop()), "weights": {"distance": 1.0, "duck": 1.0}})


def test_the_meter_needs_observations(hop: Task) -> None:
    with pytest.raises(FigureError):
        TaskMeter(hop, 1).terms()


def test_tracked_sites_are_measured_from_the_first_tick() -> None:
    task = humanoid_reach("nose")
    figure = task.figure
    first: list[np.ndarray] = []
    meter = TaskMeter(task, 1)

    def observe(t: float, sensors: np.ndarray, targets: np.ndarray) -> None:
        if not first:
            first.append(sensors.copy())
        meter(t, sensors, targets)

    rollout(figure, HoldPose(figure.neutral), 1, 0.2, observer=observe)
    at_rest = first[0][0]
    assert at_rest[figure.sensor_index("z_nose")] == pytest.approx(1.6, abs=0.01)
    assert at_rest[figure.sensor_index("z_hand_r")] == pytest.approx(0.815, abs=0.01)
    terms = dict(zip(task.weights, meter.terms()[0], strict=True))
    assert terms["early"] == 0.0 and terms["distance"] < -0.5  # the hand hangs far from the nose


def test_a_hand_touches_within_two_centimetres() -> None:
    """Two hands held still for 3 s, 4 cm and 1 cm from a fixed point: only the second has
    arrived, so "settled early" cannot outbid ending closer."""
    task = humanoid_reach((0.45, 1.3))
    meter = TaskMeter(task, 2)
    for k in range(31):
        t = k / 10
        sensors = sensors_for(task, time=[t, t], x_hand_r=[0.41, 0.44], z_hand_r=[1.3, 1.3])
        meter(t, sensors, np.tile(task.figure.neutral, (2, 1)))
    terms = meter.terms()
    early, distance = (list(task.weights).index(name) for name in ("early", "distance"))
    np.testing.assert_allclose(terms[:, distance], [-0.04, -0.01])
    assert terms[0, early] == 0.0 and terms[1, early] == pytest.approx(1.0)


def test_a_touch_is_held_not_swung_through() -> None:
    """Over 3 s, one hand swings through the point and is on it at the last tick; another
    rests 1 cm from it for the last second: the reach rates the farthest either gets over
    the last `TOUCH_HOLD` seconds, so only the second touches."""
    task = humanoid_reach((0.45, 1.3))
    meter = TaskMeter(task, 2)
    for k in range(31):
        t = k / 10
        swing = 0.45 + 0.1 * np.sin(2 * np.pi * (t - 3.0) / 1.2)  # through x = 0.45 at 3 s
        rest = 0.46 if t >= 2.0 else 0.2
        sensors = sensors_for(task, time=[t, t], x_hand_r=[swing, rest], z_hand_r=[1.3, 1.3])
        meter(t, sensors, np.tile(task.figure.neutral, (2, 1)))
    distance = meter.terms()[:, list(task.weights).index("distance")]
    assert TOUCH_HOLD >= 0.3 and distance[1] == pytest.approx(-0.01)
    assert distance[0] == pytest.approx(-0.1)  # the swing's far end, at 2.7 s


def test_a_hand_that_came_near_once_is_not_outranked_by_one_that_never_did() -> None:
    """At full style weight: a hand that passes the nose at 1 s and ends held 3.7 cm from
    it rates above one held 5 cm away throughout (`still` counted the first one's path)."""
    task = humanoid_reach("nose")
    meter = TaskMeter(task, 2)
    nose = {"x_nose": [0.1, 0.1], "z_nose": [1.6, 1.6]}
    for k in range(31):
        t = k / 10
        passing = 0.1 + abs(t - 1.0) * 0.05 if t < 1.74 else 0.137
        columns = {"x_hand_r": [passing, 0.15], "z_hand_r": [1.6, 1.6], **nose}
        meter(t, sensors_for(task, time=[t, t], **columns), np.tile(task.figure.neutral, (2, 1)))
    fitness = meter.terms() @ np.array(list(task.weights.values()))
    assert fitness[0] > fitness[1]


@pytest.mark.parametrize("hold", [-0.1, float("nan")])
def test_a_goal_holds_for_zero_seconds_or_more(hold: float) -> None:
    with pytest.raises(FigureError, match="holds for 0 s or more"):
        Goal(tracked=("root_x",), target=(1.0,), names=("gx",), hold=hold)
