"""Entrained spring nets: the music's force on the masses, the net's period, a dance run."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("mujoco")

from dance_helpers import song_folder
from sinews.control.music_input import MUSIC_TERMINALS, music_table
from sinews.errors import SinewsError
from sinews.experiments.figures import make_figure
from sinews.experiments.score_memory import ChunkContext
from sinews.experiments.springnet.dance import (
    DANCE_FIGURES,
    DRIVE,
    DRIVE_FORCE,
    dominant_period,
    drive_weights,
)
from sinews.experiments.springnet.score import score_chunk
from sinews.experiments.springnet.settings import MAX_TEMPI, SpringNetSettings, tempi_of
from sinews.experiments.springnet.simulate import simulate
from sinews.figures.tasks import make_task
from sinews.figures.terms import TaskMeter
from sinews.music import analyse_file


@pytest.fixture(scope="module")
def song(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Path]:
    """A 4 s drum track at 120 BPM, with the XDG folders (the analysis cache) beside it."""
    with song_folder(tmp_path_factory.mktemp("net_dance"), seconds=4.0) as song:
        yield song


def test_drive_genes_weigh_only_the_drive_columns() -> None:
    genes = np.array([[1.0, 0.0, 0.75, 0.5]])  # 2 masses x 2 drive columns
    weights = drive_weights(genes, 2, 5)
    assert weights.shape == (1, 2, 5 + len(MUSIC_TERMINALS))
    columns = [5 + MUSIC_TERMINALS.index(name) for name in DRIVE]
    expected = np.array([[1.0, -1.0], [0.5, 0.0]]) * DRIVE_FORCE
    np.testing.assert_allclose(weights[0][:, columns], expected)
    weights[0][:, columns] = 0.0
    assert not weights.any()
    np.testing.assert_allclose(drive_weights(genes, 2, 5, 90.0)[0][:, columns], expected * 3)


def test_dominant_period_finds_the_strongest_swing() -> None:
    t = np.arange(0, 10, 0.01)
    x = np.sin(2 * np.pi * t / 0.5) + 0.3 * np.sin(2 * np.pi * t / 1.7)
    assert dominant_period(x, 100) == pytest.approx(0.5, rel=0.01)
    assert dominant_period(np.stack([x, 2 * np.sin(2 * np.pi * t / 1.7)], axis=1), 100) == (
        pytest.approx(1.7, rel=0.02)
    )
    assert dominant_period(np.ones(300), 100) == np.inf


def _dance_settings(song: Path, seconds: float, **values: object) -> SpringNetSettings:
    return SpringNetSettings.from_values({"figure": "luxo", "seconds": seconds, "control_hz": 100,
        "task": "dance", "song_path": str(song), "song_hash": analyse_file(song).song_hash,
        **values})  # fmt: skip


@pytest.mark.parametrize("rate", [1.0, 1.25])
def test_a_driven_net_swings_at_the_beat_and_a_free_one_at_its_own_period(
    song: Path, rate: float
) -> None:
    period = 60.0 / analyse_file(song).tempo_bpm / rate
    assert period * rate == pytest.approx(0.5, rel=0.03)
    settings = _dance_settings(song, 3.0, masses=3, tempi=[rate])
    size, n = settings.encoding.size, settings.masses
    genes = np.full((3, settings.genome_size), 0.5)  # every mass at 0, no drive
    genes[:, n : size - n] = 0.0  # no springs
    genes[0, size:] = [0.8, 0.5, 0.5, 0.5, 0.5, 0.5]  # mass 0 feels the beat's sine
    genes[2, n : size - n] = 0.05  # springs of 5
    genes[2, size - n : size] = [0.2, 0.8, 0.5]  # masses apart: the net swings by itself
    _, net = simulate(settings, genes, record_hz=100.0, rate=rate)
    assert net is not None
    driven, still, free = (dominant_period(net[:, k], 100.0) for k in range(3))
    assert driven == pytest.approx(period, rel=0.05)
    assert still == np.inf and not net[:, 1].any()
    assert abs(free / period - 1) > 0.5


@pytest.mark.parametrize("clock", ["time", "beats"])
def test_on_the_beat_clock_a_free_net_swings_at_a_fixed_multiple_of_the_beat(
    song: Path, clock: str
) -> None:
    settings = _dance_settings(song, 3.0, masses=3, tempi=[1.25], clock=clock)
    size, n = settings.encoding.size, settings.masses
    genes = np.full((1, settings.genome_size), 0.5)  # no drive
    genes[:, :n] = 0.1  # masses of 1.09
    genes[:, n : size - n] = 0.5  # springs of 50: a swing of about 0.5 s
    genes[:, size - n : size] = [0.2, 0.8, 0.5]  # masses apart: the net swings by itself
    periods = []
    for rate in settings.tempi:
        _, net = simulate(settings, genes, record_hz=100.0, rate=rate)
        assert net is not None
        periods.append(dominant_period(net[:, 0, 0], 100.0, skip=0.0))
    ratio = periods[0] / periods[1]
    assert ratio == pytest.approx(1.25 if clock == "beats" else 1.0, rel=0.03)


def test_a_song_played_faster_is_the_same_music_sooner(song: Path) -> None:
    music = analyse_file(song)
    fast = music.played_at(1.25)
    np.testing.assert_allclose(fast.beats, music.beats / 1.25)
    assert fast.tempo_bpm == pytest.approx(1.25 * music.tempo_bpm)
    assert fast.duration == pytest.approx(music.duration / 1.25)
    # 100 ticks a second of the fast song are 80 a second of the song itself (but where a
    # tick falls half-way between two frames, rounding may pick either)
    frame = np.arange(201) / 80 * music.fps
    clear = np.abs(frame - np.floor(frame) - 0.5) > 1e-6
    np.testing.assert_allclose(music_table(fast, 100, 200)[clear],
                               music_table(music, 80, 200)[clear], atol=1e-9)  # fmt: skip
    with pytest.raises(ValueError, match="positive"):
        music.played_at(float("nan"))


def test_a_nets_dance_terms_are_the_means_over_its_tempi(song: Path) -> None:
    alone = _dance_settings(song, 3.0)
    both = _dance_settings(song, 3.0, tempi=[1.25])
    assert alone.tempi == (1.0,) and both.tempi == (1.0, 1.25)
    genes = np.random.default_rng(5).random((4, both.genome_size))
    own = score_chunk(ChunkContext(alone, None, 30.0), genes)
    mean = score_chunk(ChunkContext(both, None, 30.0), genes)
    dance = both.dance
    assert dance is not None
    meter = TaskMeter(dance, len(genes), beats=both.heard_at(1.25).beats)
    faster, _ = simulate(both, genes, observer=meter, rate=1.25)
    np.testing.assert_array_equal(mean.terms, (own.terms + meter.terms()) / 2)
    assert not (mean.failed | faster.failed | own.failed).any()
    assert not np.array_equal(mean.terms, own.terms)
    for (trajectory, _, net), (kept, _, kept_net) in zip(mean.motion, own.motion, strict=True):
        np.testing.assert_array_equal(trajectory.qpos, kept.qpos)  # the song's own tempo
        np.testing.assert_array_equal(net, kept_net)


@pytest.mark.parametrize(
    ("value", "tempi"),
    [(None, (1.0,)), ("0.8,1.25", (1.0, 0.8, 1.25)), ([1.25, 1.0], (1.0, 1.25)), ("1", (1.0,))],
)
def test_tempi_put_the_songs_own_first(value: object, tempi: tuple[float, ...]) -> None:
    assert tempi_of(value) == tempi


@pytest.mark.parametrize("value", ["0.4", "2.5", "nan", "inf", "fast", "", [], "0.6,0.7,0.8,0.9"])
def test_bad_tempi_are_refused(value: object) -> None:
    with pytest.raises(SinewsError, match="tempi"):
        tempi_of(value)
    assert MAX_TEMPI == 4


def test_a_song_too_short_for_its_fastest_tempo_is_refused(song: Path) -> None:
    settings = _dance_settings(song, 3.5, tempi=[1.5])
    with pytest.raises(SinewsError, match=r"1\.5x as fast lasts"):
        settings.heard_at(1.5)


def test_a_dancing_net_drives_only_the_dances_joints(song: Path) -> None:
    music = analyse_file(song)
    settings = SpringNetSettings.from_values({"figure": "humanoid", "seconds": 4.0,
        "control_hz": 100, "task": "dance", "song_path": str(song),
        "song_hash": music.song_hash})  # fmt: skip
    figure = make_figure("humanoid")
    dance = make_task(DANCE_FIGURES["humanoid"])
    driven = [figure.joints.index(j) for j in dance.joints]
    assert settings.masses == len(dance.joints) == 5  # one mass per driven joint
    assert settings.driven(figure).tolist() == driven
    genes = np.random.default_rng(4).random((3, settings.genome_size))
    controller = settings.controller(figure, genes)
    held = np.setdiff1d(np.arange(figure.n_actuators), driven)
    assert (controller.gain[driven] > 0).all() and not controller.gain[held].any()
    assert controller.outputs[driven].tolist() == list(range(5))
    assert figure.joints[held[0]] == "waist" and held.size == 7  # the waist and the legs
    result, _ = simulate(settings, genes)
    assert not result.failed.any()


def test_only_a_dance_stores_its_tempi_and_drive(song: Path) -> None:
    plain = SpringNetSettings.from_values({"figure": "luxo", "seconds": 1.0, "control_hz": 100})
    assert "tempi" not in plain.to_dict() and plain.tempi == (1.0,)
    assert "drive" not in plain.to_dict() and plain.drive == DRIVE_FORCE
    dance = _dance_settings(song, 3.0, tempi="1.25", drive=90)
    assert dance.to_dict()["tempi"] == [1.0, 1.25] and dance.to_dict()["drive"] == 90.0
    assert SpringNetSettings.from_values(dance.to_dict()) == dance
    older = {k: v for k, v in dance.to_dict().items() if k != "drive"}  # stored before drive
    assert SpringNetSettings.from_values(older).drive == DRIVE_FORCE
    assert "clock" not in plain.to_dict() and dance.clock == "time"
    on_beats = _dance_settings(song, 3.0, clock="beats")
    assert SpringNetSettings.from_values(on_beats.to_dict()).clock == "beats"
    older = {k: v for k, v in on_beats.to_dict().items() if k != "clock"}  # before the clock
    assert SpringNetSettings.from_values(older).clock == "time"


@pytest.mark.parametrize("value", ["sometimes", "Beats", 1, True])
def test_bad_clocks_are_refused(song: Path, value: object) -> None:
    with pytest.raises(SinewsError, match="clock must be one of time, beats"):
        _dance_settings(song, 3.0, clock=value)


def test_a_harder_drive_pushes_the_masses_harder(song: Path) -> None:
    genes = np.random.default_rng(6).random((2, _dance_settings(song, 3.0).genome_size))
    figure = make_figure("luxo")
    soft, hard = (_dance_settings(song, 3.0, drive=d).controller(figure, genes) for d in (30, 90))
    assert soft.input_weights is not None and hard.input_weights is not None
    np.testing.assert_allclose(hard.input_weights, 3 * soft.input_weights)


@pytest.mark.parametrize("value", [0, -5, float("nan"), float("inf"), 1001, "hard", True])
def test_bad_drives_are_refused(song: Path, value: object) -> None:
    with pytest.raises(SinewsError, match="drive"):
        _dance_settings(song, 3.0, drive=value)
