"""The dance task: music terminals in its input map, and its terms on hand-made motion."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("mujoco")

from sinews.control.hold import HoldPose
from sinews.control.music_input import MUSIC_TERMINALS
from sinews.figures import FigureError, rollout
from sinews.figures.tasks import (
    DANCE_STYLE,
    LUXO_LYING,
    TASKS,
    TaskMeter,
    luxo_dance,
    make_task,
)

BEATS = np.arange(0.25, 4.0, 0.5)
HZ = 100


DANCES = sorted(name for name in TASKS if name.endswith("-dance"))


def test_every_figure_dances() -> None:
    assert DANCES == ["humanoid-dance", "humanoid3d-dance", "luxo-dance", "luxo3d-dance",
                      "snake-dance"]  # fmt: skip


@pytest.mark.parametrize("name", DANCES)
def test_the_dance_hears_the_music_after_the_sensors(name: str) -> None:
    task = make_task(name, seconds=2.0)
    assert task.seconds == 2.0 and next(iter(task.weights)) == "lift"
    assert task.terminals[-len(MUSIC_TERMINALS) :] == MUSIC_TERMINALS
    weights, offset = task.input_map()
    n = task.figure.n_sensors
    assert weights.shape == (n + len(MUSIC_TERMINALS), len(task.terminals))
    assert np.array_equal(weights[n:, -len(MUSIC_TERMINALS) :], np.eye(len(MUSIC_TERMINALS)))
    assert not weights[n:, : -len(MUSIC_TERMINALS)].any() and not offset.any()


@pytest.mark.parametrize(
    ("name", "joints", "spot", "weights"),
    [
        ("luxo-dance", ("base_hinge", "elbow", "neck"), ("root_x",), DANCE_STYLE),
        ("luxo3d-dance", ("base_hinge", "elbow", "neck"), ("root_x", "root_y"), DANCE_STYLE),
        ("humanoid-dance", ("neck", "shoulder_l", "elbow_l", "shoulder_r", "elbow_r"),
         ("root_x",), DANCE_STYLE),
        ("humanoid3d-dance", ("shoulder_x_l", "shoulder_y_l", "shoulder_z_l", "elbow_l",
                              "shoulder_x_r", "shoulder_y_r", "shoulder_z_r", "elbow_r",
                              "waist_z", "neck_y", "neck_z"), ("root_x", "root_y"), DANCE_STYLE),
        ("snake-dance", ("waist", "neck"), ("root_x",),
         {**DANCE_STYLE, "head": 0.0, "fallen": 0.0}),  # it lies on the floor, head down
    ],
)  # fmt: skip
def test_each_dance_drives_its_joints_and_weighs_its_terms(
    name: str, joints: tuple[str, ...], spot: tuple[str, ...], weights: dict[str, float]
) -> None:
    task = make_task(name)
    assert task.joints == joints and task.seconds == 10.0
    assert dict(task.weights) == {"lift": 1.0, **weights}
    assert task.goal.tracked == spot and task.goal.target == (0.0,) * len(spot)
    assert {f"q_{j}" for j in joints} <= set(task.sensors)  # it sees what it moves
    assert "time" in task.sensors and not task.goal.names


def test_a_dance_is_not_measured_without_beats() -> None:
    with pytest.raises(FigureError, match="beats"):
        TaskMeter(luxo_dance(), 1)


def measure(angles: np.ndarray, root_x: np.ndarray | None = None) -> dict[str, np.ndarray]:
    """The dance's terms of (T, P, 3) driven angles at HZ (root at 0 unless given)."""
    task = luxo_dance(seconds=(len(angles) - 1) / HZ)
    figure = task.figure
    meter = TaskMeter(task, angles.shape[1], beats=BEATS)
    sensors = np.zeros((angles.shape[1], figure.n_sensors))
    columns = [figure.sensor_index(f"q_{j}") for j in task.joints]
    targets = np.zeros((angles.shape[1], figure.n_actuators))
    for k, row in enumerate(angles):
        sensors[:, columns] = row
        if root_x is not None:
            sensors[:, figure.sensor_index("root_x")] = root_x[k]
        meter(k / HZ, sensors, targets)
    return dict(zip(task.weights, meter.terms().T, strict=True))


def swing(phase: float, amplitude: float = 0.3) -> np.ndarray:
    """(T,) an angle swinging once a beat, at rest at its turns: on the beats and halfway
    between them, moved by ``phase`` of a beat."""
    t = np.arange(4 * HZ + 1) / HZ
    return amplitude * (1.0 - np.cos(2 * np.pi * (t - 0.25 - phase * 0.5) / 0.5))


def test_pausing_on_the_beat_lifts_and_off_it_does_not() -> None:
    on, off = swing(0.0), swing(0.25)  # turns on the beats; on quarter beats
    angles = np.stack([np.stack([on] * 3, axis=1), np.stack([off] * 3, axis=1)], axis=1)
    terms = measure(angles)
    assert terms["lift"][0] > 0.5
    assert terms["lift"][1] < 0.1
    assert terms["joints"].tolist() == [0.0, 0.0]  # every joint swings 0.21 rad
    assert (terms["smooth"] > -0.35).all()  # a 2 Hz swing keeps 71 % of its energy below 4 Hz


def test_the_style_terms_see_idle_joints_jerks_and_wandering() -> None:
    t = np.arange(4 * HZ + 1)
    idle = np.zeros((len(t), 3))
    idle[:, 0] = swing(0.0)
    jerky = np.stack([0.2 * (t % 6 < 3)] * 3, axis=1).astype(np.float64)
    terms = measure(np.stack([idle, jerky], axis=1), root_x=t / len(t))
    assert terms["joints"][0] == pytest.approx(-2 / 3)  # two of three joints never move
    assert terms["smooth"][1] < -0.5  # a 17 Hz square wave
    assert terms["spot"] == pytest.approx(-np.mean(t / len(t)))


def test_a_lamp_with_its_shade_on_the_floor_is_down() -> None:
    """Standing, the shade is 0.39 m up; a lamp lying on its side beating its shade on the
    floor touches it only now and then, so the shade's height is what says it is down."""
    task = luxo_dance(seconds=1.0)
    figure = task.figure
    meter = TaskMeter(task, 2, beats=BEATS)
    held = np.tile(figure.neutral, (2, 1))
    standing = rollout(figure, HoldPose(figure.neutral), 1, 0.5, nthread=1, record=True)
    assert standing.body_pos is not None and standing.body_pos[-1, 0, -1, 2] > LUXO_LYING + 0.15
    sensors = np.zeros((2, figure.n_sensors))
    sensors[:, figure.sensor_index("z_shade")] = [0.39, LUXO_LYING - 0.01]
    for k in range(HZ + 1):
        meter(k / HZ, sensors, held)
    fallen = dict(zip(task.weights, meter.terms().T, strict=True))["fallen"]
    assert fallen.tolist() == [0.0, -1.0]
