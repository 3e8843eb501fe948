"""The figure builders and `Figure.from_mjcf`: joints, servos, sensors, bodies, errors."""

from __future__ import annotations

import subprocess
import sys
from collections.abc import Callable

import numpy as np
import pytest

pytest.importorskip("mujoco")

from sinews.errors import SinewsError
from sinews.figures import (
    Figure,
    FigureError,
    humanoid,
    luxo,
    luxo_mjcf,
    sensor_columns,
    snake,
)

HUMANOID_JOINTS = (
    "waist",
    "neck",
    "shoulder_l",
    "elbow_l",
    "shoulder_r",
    "elbow_r",
    "hip_l",
    "knee_l",
    "ankle_l",
    "hip_r",
    "knee_r",
    "ankle_r",
)

CASES = [
    (luxo, ("base_hinge", "elbow", "neck"), ("base",), ("head",)),
    (snake, ("waist", "neck"), ("tail", "middle"), ("head",)),
    (humanoid, HUMANOID_JOINTS, ("foot_l", "foot_r"), ("head",)),
]


@pytest.mark.parametrize(("build", "joints", "base", "head"), CASES)
def test_builtin_figures_have_the_documented_parts(
    build: Callable[[], Figure], joints: tuple[str, ...], base: tuple[str, ...],
    head: tuple[str, ...],
) -> None:  # fmt: skip
    figure = build()
    model = figure.model()
    assert figure.joints == joints
    assert figure.base_bodies == base
    assert figure.head_bodies == head
    assert model.nu == figure.n_actuators == len(joints)
    assert [model.actuator(a).name for a in range(model.nu)] == list(joints)
    assert [model.joint(i).name for i in range(3)] == ["root_x", "root_z", "root_pitch"]
    assert model.opt.integrator == 3  # mjINT_IMPLICITFAST
    np.testing.assert_array_equal(figure.neutral, np.zeros(len(joints)))
    assert (figure.kp > 0).all() and (figure.kv > 0).all()
    assert (figure.joint_range[:, 0] < 0).all() and (figure.joint_range[:, 1] > 0).all()
    limbs = tuple(b for b in figure.body_names if b not in base + head)
    assert figure.limb_bodies == (() if build is snake else limbs)  # a snake lies on the floor
    contact = tuple(dict.fromkeys(base + head + figure.limb_bodies))
    assert figure.sensor_names == sensor_columns(joints, contact)
    assert figure.n_sensors == 1 + 2 * (3 + len(joints)) + 2 * len(contact)
    assert figure.sensor_names[:4] == ("time", "root_x", "root_z", "root_pitch")
    assert figure.sensor_index(f"q_{joints[0]}") == 4
    for body in contact:
        assert model.sensor(f"contact_{body}").dim[0] == 3
    assert len(figure.body_names) == model.nbody - 1
    assert len(figure.edges) == len(figure.body_names) - 1  # one tree


def test_humanoid_has_between_10_and_15_joints_and_no_self_collision() -> None:
    model = humanoid().model()
    assert 10 <= model.nu <= 15
    floor = model.geom("floor").id
    for g in range(model.ngeom):
        if g != floor:
            assert model.geom_contype[g] == 1 and model.geom_conaffinity[g] == 0


def test_luxo_edges_follow_the_chain() -> None:
    figure = luxo()
    assert figure.body_names == ("base", "arm_lower", "arm_upper", "head")
    assert figure.edges.tolist() == [[0, 1], [1, 2], [2, 3]]


def test_each_model_is_a_fresh_copy_that_steps_as_a_compiled_one() -> None:
    import mujoco

    figure = luxo()
    first, second = figure.model(timestep=0.002), figure.model()
    assert first.opt.timestep == 0.002 and second.opt.timestep != 0.002  # copies, not shared
    first.geom_friction[:] = 0.0
    assert figure.model().geom_friction.any()
    compiled = mujoco.MjModel.from_xml_string(figure.xml)
    states = []
    for model in (figure.model(), compiled):
        data = mujoco.MjData(model)
        data.ctrl[:] = 0.3
        for _ in range(200):
            mujoco.mj_step(model, data)
        states.append(data.qpos.copy())
    np.testing.assert_array_equal(*states)


def test_from_mjcf_accepts_a_users_figure_and_its_own_output() -> None:
    xml = """<mujoco><compiler angle="radian"/><worldbody>
      <geom name="floor" type="plane" size="1 1 0.1"/>
      <body name="hull" pos="0 0 0.1">
        <joint name="x" type="slide" axis="1 0 0"/><joint name="z" type="slide" axis="0 0 1"/>
        <joint name="pitch" type="hinge" axis="0 1 0"/>
        <geom type="box" size="0.2 0.1 0.1" mass="2"/>
        <body name="flap" pos="0.2 0 0">
          <joint name="hinge" type="hinge" axis="0 1 0" range="-1 1"/>
          <geom type="capsule" fromto="0 0 0 0.2 0 0" size="0.02" mass="0.2"/>
        </body>
      </body></worldbody>
      <actuator><position joint="hinge" kp="4" kv="0.2"/></actuator>
    </mujoco>"""
    figure = Figure.from_mjcf(xml, name="boat", base_bodies=["hull"], neutral=[0.25])
    assert figure.joints == ("hinge",)
    assert figure.kp.tolist() == [4.0] and figure.kv.tolist() == [0.2]
    assert figure.neutral.tolist() == [0.25]
    assert figure.joint_range.tolist() == [[-1.0, 1.0]]
    assert figure.sensor_names[-2:] == ("fx_hull", "fz_hull")
    again = Figure.from_mjcf(figure.xml, name="boat", base_bodies=["hull"])
    assert again.sensor_names == figure.sensor_names
    assert again.model().nsensor == 1


@pytest.mark.parametrize(
    ("change", "message"),
    [
        (lambda x: x.replace('axis="1 0 0"', 'axis="0 1 0"', 1), "slide x"),
        (lambda x: x.replace("<position", '<motor joint="neck"/><position', 1), "not a position"),
        (lambda x: x.replace("<mujoco", "<mujoco><oops", 1), "does not compile"),
    ],
)
def test_from_mjcf_rejects_unusable_models(change: Callable[[str], str], message: str) -> None:
    with pytest.raises(FigureError, match=message):
        Figure.from_mjcf(change(luxo_mjcf()), name="bad", base_bodies=["base"])


def test_from_mjcf_names_missing_bodies_and_bad_neutral() -> None:
    with pytest.raises(FigureError, match="no body named 'foot'"):
        Figure.from_mjcf(luxo_mjcf(), name="x", base_bodies=["foot"])
    with pytest.raises(FigureError, match="neutral"):
        Figure.from_mjcf(luxo_mjcf(), name="x", base_bodies=["base"], neutral=[0.0])
    with pytest.raises(FigureError, match="no sensor column"):
        luxo().sensor_index("q_knee")


def test_missing_mujoco_is_reported_at_use_not_at_import(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(sys.modules, "mujoco", None)
    with pytest.raises(SinewsError, match=r"sinews\[figures\]"):
        luxo()


def test_importing_sinews_and_figures_does_not_load_mujoco() -> None:
    code = "import sys, sinews, sinews.figures, sinews.control; print('mujoco' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"
