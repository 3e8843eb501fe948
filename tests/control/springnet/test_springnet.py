"""Spring nets: kernels against the numpy reference, the analytic 2-mass frequency, genomes."""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from sinews.control import HoldPose
from sinews.control.springnet import (
    MASS_RANGE,
    POSITION_RANGE,
    SPRING_RANGE,
    SpringNetController,
    SpringNetError,
    SpringNetGenome,
    integrate,
    integrate_reference,
    stable_time_step,
)
from sinews.control.springnet.dynamics import (
    integrate_serial,
    sensor_forces,
    sensor_forces_serial,
)

FloatArray = npt.NDArray[np.float64]


def _state(genome: SpringNetGenome) -> tuple[FloatArray, FloatArray]:
    return genome.positions.copy(), np.zeros_like(genome.positions)


@settings(max_examples=15, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    n_nets=st.integers(1, 40),
    n_masses=st.integers(1, 7),
    n_steps=st.integers(1, 400),
)
def test_numba_kernels_match_the_numpy_reference(
    seed: int, n_nets: int, n_masses: int, n_steps: int
) -> None:
    rng = np.random.default_rng(seed)
    genome = SpringNetGenome.random(rng, n_nets, n_masses)
    force = rng.normal(0.0, 5.0, genome.positions.shape)
    ts = 0.5 * min(stable_time_step(genome), 0.01)
    runs = []
    for kernel in (integrate, integrate_serial, integrate_reference):
        x, v = _state(genome)
        kernel(genome.masses, genome.springs, x, v, force, n_steps, ts)
        runs.append((x, v))
    (x_par, v_par), (x_ser, v_ser), (x_ref, v_ref) = runs
    np.testing.assert_array_equal(x_par, x_ser)  # bit for bit: no dependence on threads
    np.testing.assert_array_equal(v_par, v_ser)
    np.testing.assert_allclose(x_par, x_ref, rtol=0, atol=1e-9)
    np.testing.assert_allclose(v_par, v_ref, rtol=0, atol=1e-9 * max(1.0, np.abs(v_ref).max()))


def test_sensor_force_kernels_agree_with_numpy() -> None:
    rng = np.random.default_rng(1)
    weights = rng.normal(size=(50, 4, 17))
    sensors = rng.normal(size=(50, 17))
    parallel, serial = np.empty((50, 4)), np.empty((50, 4))
    sensor_forces(weights, sensors, parallel)
    sensor_forces_serial(weights, sensors, serial)
    np.testing.assert_array_equal(parallel, serial)
    np.testing.assert_allclose(parallel, np.einsum("pis,ps->pi", weights, sensors), atol=1e-12)


def _two_masses(m1: float, m2: float, k: float, x1: float, x2: float) -> SpringNetGenome:
    springs = np.array([[[0.0, k], [k, 0.0]]])
    return SpringNetGenome(np.array([[m1, m2]]), springs, np.array([[x1, x2]]))


@pytest.mark.parametrize(("m1", "m2", "k"), [(1.0, 1.0, 40.0), (0.5, 2.0, 10.0)])
def test_two_masses_oscillate_at_the_analytic_frequency(m1: float, m2: float, k: float) -> None:
    genome = _two_masses(m1, m2, k, -0.5, 0.5)
    omega = math.sqrt(k * (1 / m1 + 1 / m2))  # zero rest length: the gap obeys r'' = -ω² r
    ts = 1e-3  # the scheme's own frequency error is ~(ω ts)² / 24 < 1e-5
    n_steps = round(10 * 2 * math.pi / omega / ts)  # ten periods
    x, v = _state(genome)
    gap = np.empty(n_steps)
    for step in range(n_steps):
        integrate(genome.masses, genome.springs, x, v, np.zeros_like(x), 1, ts)
        gap[step] = x[0, 1] - x[0, 0]
    rising = np.flatnonzero((gap[:-1] < 0) & (gap[1:] >= 0))
    crossings = rising - gap[rising] / (gap[rising + 1] - gap[rising])  # linear interpolation
    period = np.diff(crossings).mean() * ts
    assert period == pytest.approx(2 * math.pi / omega, rel=1e-4)
    assert np.abs(gap).max() == pytest.approx(1.0, rel=1e-3)  # bounded, no energy drift
    centre = (m1 * x[0, 0] + m2 * x[0, 1]) / (m1 + m2)
    assert centre == pytest.approx((m1 * -0.5 + m2 * 0.5) / (m1 + m2), abs=1e-12)


def test_a_net_at_one_point_or_without_springs_stays_still() -> None:
    still = _two_masses(1.0, 1.0, 30.0, 0.2, 0.2)
    loose = _two_masses(1.0, 1.0, 0.0, -0.3, 0.4)
    for genome in (still, loose):
        x, v = _state(genome)
        integrate(genome.masses, genome.springs, x, v, np.zeros_like(x), 100, 0.01)
        np.testing.assert_array_equal(x, genome.positions)


def test_random_genomes_are_valid_reproducible_and_follow_a_topology() -> None:
    chain = np.eye(5, k=1, dtype=bool)
    a = SpringNetGenome.random(np.random.default_rng(4), 20, 5, topology=chain)
    b = SpringNetGenome.random(np.random.default_rng(4), 20, 5, topology=chain)
    np.testing.assert_array_equal(a.springs, b.springs)
    assert a.n_individuals == 20 and a.n_masses == 5
    assert (a.masses >= MASS_RANGE[0]).all() and (a.masses <= MASS_RANGE[1]).all()
    assert (a.springs >= SPRING_RANGE[0]).all() and (a.springs <= SPRING_RANGE[1]).all()
    assert np.abs(a.positions).max() <= POSITION_RANGE[1]
    allowed = chain | chain.T
    assert (a.springs[:, ~allowed] == 0).all()
    assert (a.springs[:, allowed] > 0).all()
    picked = a.take([3, 0])
    np.testing.assert_array_equal(picked.masses, a.masses[[3, 0]])


@pytest.mark.parametrize(
    ("field", "value", "message"),
    [
        ("masses", np.full((2, 3), 0.0), "masses"),
        ("positions", np.full((2, 3), 5.0), "positions"),
        ("springs", np.ones((2, 3, 3)) - np.eye(3) + np.eye(3, k=1), "symmetric"),
        ("springs", np.ones((2, 3, 3)), "diagonal"),
        ("springs", np.zeros((2, 3)), "shape"),
    ],
)
def test_genome_validation_names_the_field(field: str, value: FloatArray, message: str) -> None:
    fields = {
        "masses": np.ones((2, 3)),
        "springs": np.zeros((2, 3, 3)),
        "positions": np.zeros((2, 3)),
    }
    fields[field] = value
    with pytest.raises(SpringNetError, match=message):
        SpringNetGenome(**fields)


def test_controller_maps_output_masses_through_gain_and_offset() -> None:
    genome = SpringNetGenome.random(np.random.default_rng(2), 6, 3)
    offset = np.array([0.1, -0.2])
    controller = SpringNetController(genome, outputs=[2, 0], gain=[2.0, -1.0], offset=offset)
    controller.reset(6)
    sensors = np.zeros((6, 5))
    first = controller.control(0.0, sensors)
    np.testing.assert_array_equal(first, offset + [2.0, -1.0] * genome.positions[:, [2, 0]])
    later = controller.control(0.5, sensors).copy()
    x, v = _state(genome)
    integrate_reference(genome.masses, genome.springs, x, v, np.zeros_like(x), 100, 0.005)
    np.testing.assert_allclose(later, offset + [2.0, -1.0] * x[:, [2, 0]], atol=1e-9)
    controller.reset(6)
    np.testing.assert_array_equal(controller.control(0.0, sensors), first)


def test_sensor_input_pushes_the_net() -> None:
    genome = SpringNetGenome.random(np.random.default_rng(5), 4, 3)
    sensors = np.ones((4, 2))
    free = SpringNetController(genome, outputs=[0])
    zero = SpringNetController(genome, outputs=[0], input_weights=np.zeros((3, 2)))
    pushed = SpringNetController(genome, outputs=[0], input_weights=np.full((3, 2), 0.5))
    outs = []
    for controller in (free, zero, pushed):
        controller.reset(4)
        for tick in range(50):
            out = controller.control(tick / 100, sensors)
        outs.append(out)
    np.testing.assert_array_equal(outs[0], outs[1])
    # a constant push of 1 N on every mass accelerates the centre of mass at 3 / M
    total = genome.masses.sum(axis=1)
    centre = (pushed.x * genome.masses).sum(axis=1) / total
    start = (genome.positions * genome.masses).sum(axis=1) / total
    steps = 98  # floor(0.49 / 0.005)
    expected = 0.5 * 3.0 / total * 0.005**2 * steps * (steps + 1)
    np.testing.assert_allclose(centre - start, expected, rtol=1e-9)


def test_controller_rejects_bad_settings() -> None:
    genome = SpringNetGenome.random(np.random.default_rng(6), 3, 4)
    with pytest.raises(SpringNetError, match="outputs"):
        SpringNetController(genome, outputs=[4])
    with pytest.raises(SpringNetError, match="gain"):
        SpringNetController(genome, outputs=[0, 1], gain=[1.0, 2.0, 3.0])
    with pytest.raises(SpringNetError, match="ts"):
        SpringNetController(genome, outputs=[0], ts=2 * stable_time_step(genome))
    with pytest.raises(SpringNetError, match="input_weights"):
        SpringNetController(genome, outputs=[0], input_weights=np.zeros((5, 2)))
    controller = SpringNetController(genome, outputs=[0], input_weights=np.zeros((4, 2)))
    with pytest.raises(SpringNetError, match="cannot drive"):
        controller.reset(5)
    controller.reset(3)
    with pytest.raises(SpringNetError, match="expect 2 sensors"):
        controller.control(0.1, np.zeros((3, 7)))


def test_hold_pose_answers_its_targets_for_every_row() -> None:
    hold = HoldPose([0.1, 0.2])
    hold.reset(3)
    np.testing.assert_array_equal(hold.control(1.0, np.zeros((3, 4))), [[0.1, 0.2]] * 3)
