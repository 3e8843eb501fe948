"""The 3D figures: parts, degrees of freedom, mass, rest, sensors in the heading frame."""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
import pytest

pytest.importorskip("mujoco")

from sinews.control import HoldPose
from sinews.figures import rollout
from sinews.figures.figure import Figure, FigureError
from sinews.figures.humanoid3d import HUMANOID3D_JOINTS, humanoid3d
from sinews.figures.luxo3d import LuxoShape3D, luxo3d, luxo3d_mjcf
from sinews.figures.tasks import standing_height


@pytest.fixture(scope="module")
def lamp() -> Figure:
    return luxo3d()


@pytest.fixture(scope="module")
def person() -> Figure:
    return humanoid3d()


def test_the_lamp_has_four_links_three_hinges_and_a_free_base(lamp: Figure) -> None:
    model = lamp.model()
    assert lamp.root == "free"
    assert lamp.joints == ("base_hinge", "elbow", "neck") and lamp.heading_joint is None
    assert model.nbody - 1 == 4  # base, two arms, head
    assert model.nv == 6 + 3 and model.nu == 3
    assert model.jnt_type[0] == 0  # mjJNT_FREE
    assert model.body_subtreemass[1] == pytest.approx(1.15)
    assert lamp.base_bodies == ("base",) and lamp.head_bodies == ("head",)


def test_the_humanoid_has_at_least_28_dof_and_every_hinge_servoed(person: Figure) -> None:
    model = person.model()
    assert model.nv == 31 >= 28  # the free root's 6 and 25 hinges
    assert person.joints == HUMANOID3D_JOINTS and model.nu == 25
    assert (model.jnt_limited[1:] == 1).all()  # every hinge has a range
    assert 60.0 < model.body_subtreemass[1] < 80.0  # an adult
    assert 1.7 < standing_height(person) < 1.85
    # the right arm's sideways range mirrors the left's
    left = person.joint_range[person.joints.index("shoulder_x_l")]
    right = person.joint_range[person.joints.index("shoulder_x_r")]
    np.testing.assert_allclose(right, -left[::-1])


@pytest.mark.parametrize("build", [luxo3d, humanoid3d])
def test_3d_figures_rest_on_their_feet_under_a_pd_hold(build: Callable[[], Figure]) -> None:
    figure = build()
    result = rollout(figure, HoldPose(figure.neutral), 2, 2.0, record=True, nthread=1)
    assert not result.failed.any()
    assert result.qpos is not None
    start, end = result.qpos[0, 0], result.qpos[-1, 0]
    assert abs(end[0] - start[0]) < 0.01 and abs(end[1] - start[1]) < 0.01
    assert abs(end[2] - start[2]) < 0.01  # no sinking, no falling
    assert abs(end[3]) > 0.999  # still upright (quaternion w)


def test_free_root_sensors_read_position_heading_and_the_heading_frame(lamp: Figure) -> None:
    """Turn the lamp by 90° at (1, 2): the base's front (a site) lies ahead in its frame."""
    import mujoco

    figure = Figure.from_mjcf(
        lamp.xml, name="lamp", base_bodies=("base",), sites=("base_front",), root="free"
    )
    from sinews.figures.sensors import make_reader

    model = figure.model()
    data = mujoco.MjData(model)
    data.qpos[:3] = (1.0, 2.0, model.qpos0[2] + 0.1)
    data.qpos[3:7] = (math.cos(math.pi / 4), 0, 0, math.sin(math.pi / 4))  # yaw 90°
    data.qvel[:3] = (0.0, 1.5, 0.0)  # moving along +y: forward for a lamp facing +y
    mujoco.mj_forward(model, data)
    reader = make_reader(model, figure.joints, figure.contact_bodies, figure.sites, "free")
    out = np.zeros((1, reader.n_columns))
    reader.read(out, data.time * np.ones(1), data.qpos[None], data.qvel[None],
                data.sensordata[None])  # fmt: skip
    column = dict(zip(figure.sensor_names, out[0], strict=True))
    assert len(figure.sensor_names) == reader.n_columns
    assert column["root_x"] == pytest.approx(1.0) and column["root_y"] == pytest.approx(2.0)
    assert column["root_z"] == pytest.approx(0.1)
    assert column["root_yaw"] == pytest.approx(math.pi / 2)
    assert column["root_tilt"] == pytest.approx(0.0, abs=1e-9)
    assert column["root_vf"] == pytest.approx(1.5) and column["root_vl"] == pytest.approx(0.0)
    front = 0.8 * LuxoShape3D().base_radius
    assert column["f_base_front"] == pytest.approx(front)
    assert column["l_base_front"] == pytest.approx(0.0, abs=1e-9)
    assert column["x_base_front"] == pytest.approx(1.0, abs=1e-9)
    assert column["y_base_front"] == pytest.approx(2.0 + front)


def test_a_tipped_base_reads_its_tilt_and_lean(lamp: Figure) -> None:
    import mujoco

    from sinews.figures.sensors import make_reader

    model = lamp.model()
    data = mujoco.MjData(model)
    data.qpos[3:7] = (math.cos(0.2), 0, math.sin(0.2), 0)  # pitched 0.4 rad about y
    reader = make_reader(model, lamp.joints, lamp.contact_bodies, (), "free")
    out = np.zeros((1, reader.n_columns))
    reader.read(out, np.zeros(1), data.qpos[None], data.qvel[None], data.sensordata[None])
    column = dict(zip(lamp.sensor_names, out[0], strict=True))
    assert column["root_tilt"] == pytest.approx(0.4)
    assert column["root_lean_f"] == pytest.approx(math.sin(0.4))  # leaning forward
    assert column["root_lean_l"] == pytest.approx(0.0, abs=1e-12)


def test_a_free_root_is_checked() -> None:
    planar = luxo3d_mjcf().replace('<freejoint name="root"/>', "")
    with pytest.raises(FigureError, match="free joint"):
        Figure.from_mjcf(planar, name="x", base_bodies=("base",), root="free")
    with pytest.raises(FigureError, match="planar"):
        Figure.from_mjcf(luxo3d_mjcf(), name="x", base_bodies=("base",), root="sideways")


def test_a_lamp_of_three_pitch_hinges_cannot_turn_but_a_swivel_or_twist_can() -> None:
    """Why the neck twists (or the arm swivels): with three parallel pitch axes nothing
    turns the lamp."""
    rng = np.random.default_rng(0)
    n = 16
    amps, phases = rng.uniform(-1.2, 1.2, (n, 3)), rng.uniform(0, 2 * np.pi, (n, 3))

    class Swing:
        def reset(self, n_individuals: int) -> None:
            pass

        def control(self, t: float, sensors: np.ndarray) -> np.ndarray:
            return np.clip(amps * np.sin(2 * np.pi * 1.5 * t + phases), -1.2, 1.2)

    def out_of_plane(figure: Figure) -> np.ndarray:
        """(n,) how far each lamp left the x-z plane: |y| plus the tilt of its y axis."""
        result = rollout(figure, Swing(), n, 2.0, record=True, nthread=1)
        assert result.qpos is not None
        y = result.qpos[:, :, 1]
        qx, qz = result.qpos[:, :, 4], result.qpos[:, :, 6]
        r11 = 1 - 2 * (qx * qx + qz * qz)  # world y of the base's y axis
        return (np.abs(y) + (1 - r11)).max(axis=0)

    assert out_of_plane(luxo3d(LuxoShape3D(swivel=False, neck_axis="pitch"))).max() < 1e-6
    assert (out_of_plane(luxo3d()) > 0.1).sum() >= n // 2  # the neck twists
    assert (out_of_plane(swivel_lamp()) > 0.1).sum() >= n // 2


def swivel_lamp() -> Figure:
    return luxo3d(LuxoShape3D(swivel=True, neck_axis="fixed"))


def test_the_swivel_lamp_has_four_links_and_three_hinges_the_first_its_heading() -> None:
    lamp = swivel_lamp()
    model = lamp.model()
    assert lamp.joints == ("swivel", "base_hinge", "elbow") and lamp.heading_joint == "swivel"
    assert model.nbody - 1 == 4 and model.nv == 6 + 3 and model.nu == 3


def test_the_heading_follows_the_swivel() -> None:
    """Swivel the arm by 0.5 rad on a base facing +x: the lamp heads 0.5 rad left, and a
    point ahead on the lower arm's x axis lies dead ahead in its frame."""
    import mujoco

    from sinews.figures.sensors import make_reader

    xml = swivel_lamp().xml.replace(
        '<geom name="arm_lower"', '<site name="tip" pos="0.2 0 0"/><geom name="arm_lower"'
    )
    figure = Figure.from_mjcf(xml, name="lamp", base_bodies=("base",), sites=("tip",),
                              root="free", heading_joint="swivel")  # fmt: skip
    model = figure.model()
    data = mujoco.MjData(model)
    data.qpos[model.joint("swivel").qposadr[0]] = 0.5
    data.qvel[model.joint("swivel").dofadr[0]] = 2.0
    mujoco.mj_forward(model, data)
    reader = make_reader(model, figure.joints, figure.contact_bodies, figure.sites, "free",
                         "swivel")  # fmt: skip
    out = np.zeros((1, reader.n_columns))
    reader.read(out, np.zeros(1), data.qpos[None], data.qvel[None], data.sensordata[None])
    column = dict(zip(figure.sensor_names, out[0], strict=True))
    assert column["root_yaw"] == pytest.approx(0.5)
    assert column["root_wz"] == pytest.approx(2.0)
    assert column["l_tip"] == pytest.approx(0.0, abs=1e-9) and column["f_tip"] > 0.1


def test_only_a_free_roots_actuated_hinge_can_carry_the_heading(lamp: Figure) -> None:
    with pytest.raises(FigureError, match="heading joint"):
        Figure.from_mjcf(lamp.xml, name="x", base_bodies=("base",), root="free",
                         heading_joint="nothing")  # fmt: skip
