"""Song analysis against ground truth: demo songs with exact beats and kicks, CC0 loops."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import numpy.typing as npt
import pytest
import scipy.signal

from sinews.music import Audio, DemoSong, MusicFeatures, analyse, load_audio

DATA = Path(__file__).resolve().parents[1] / "data"
BEAT_TOLERANCE_S = 0.07
KICK_TOLERANCE_S = 0.05
KICK_BANDS_HZ = (35.0, 70.0)  # where the demo kicks' bodies (150 → 48 Hz sweeps) ring


def f_measure(found: npt.ArrayLike, truth: npt.ArrayLike, tolerance: float) -> float:
    """F-measure of event times, each true event matching at most one found event."""
    found = np.sort(np.asarray(found, dtype=float))
    truth = np.asarray(truth, dtype=float)
    if len(found) == 0 or len(truth) == 0:
        return 0.0
    used = np.zeros(len(found), dtype=bool)
    hits = 0
    for t in truth:
        gaps = np.where(used, np.inf, np.abs(found - t))
        best = int(np.argmin(gaps))
        if gaps[best] <= tolerance:
            used[best] = True
            hits += 1
    return 2.0 * hits / (len(found) + len(truth))


def kick_events(features: MusicFeatures) -> npt.NDArray[np.float64]:
    """Times when any kick band fires, merging firings within 0.1 s into one event."""
    centres = features.band_centres_hz
    bands = (centres >= KICK_BANDS_HZ[0]) & (centres <= KICK_BANDS_HZ[1])
    frames = np.flatnonzero(features.triggers[:, bands].any(axis=1))
    starts = frames[np.diff(frames, prepend=-(10**9)) > 0.1 * features.fps]
    return starts / features.fps


def test_f_measure_helper() -> None:
    assert f_measure([1.0, 2.0], [1.0, 2.0], 0.05) == 1.0
    assert f_measure([1.0, 1.01], [1.0], 0.05) == pytest.approx(2 / 3)
    assert f_measure([], [1.0], 0.05) == 0.0


@pytest.mark.parametrize("name", ["groove", "sway"])
def test_beats_of_the_demo_songs(
    analysed: dict[str, tuple[DemoSong, MusicFeatures]], name: str
) -> None:
    song, features = analysed[name]
    assert features.tempo_bpm == pytest.approx(song.bpm, rel=0.01)
    assert f_measure(features.beats, song.beats, BEAT_TOLERANCE_S) >= 0.95


@pytest.mark.parametrize("name", ["groove", "sway"])
def test_kick_band_triggers_fire_on_the_kicks(
    analysed: dict[str, tuple[DemoSong, MusicFeatures]], name: str
) -> None:
    song, features = analysed[name]
    assert f_measure(kick_events(features), song.kicks, KICK_TOLERANCE_S) >= 0.9


@pytest.mark.parametrize(
    ("loop", "bpm"), [("loop_breakbeat", 126.0), ("loop_mika", 120.0), ("loop_compus", 148.0)]
)
def test_tempo_of_cc0_loops(loop: str, bpm: float) -> None:
    # The loops last 2-8 s; played as loops (repeated to at least 16 s) they have a tempo.
    audio = load_audio(DATA / f"{loop}.flac")
    repeats = int(np.ceil(16.0 / audio.duration))
    features = analyse(Audio(np.tile(audio.samples, repeats), audio.sample_rate))
    assert features.tempo_bpm == pytest.approx(bpm, rel=0.04)  # an octave error fails
    intervals = np.diff(features.beats)
    assert np.median(intervals) == pytest.approx(60.0 / bpm, rel=0.04)


def test_a_quiet_master_gives_the_same_features(groove_audio: Audio) -> None:
    loud = analyse(groove_audio)
    quiet_samples = (groove_audio.samples * 10 ** (-20 / 20)).astype(np.float32)
    quiet = analyse(Audio(quiet_samples, groove_audio.sample_rate))
    difference = np.abs(loud.levels - quiet.levels)
    assert difference.mean() < 0.05 and difference.max() < 1.0
    assert np.mean(loud.triggers == quiet.triggers) > 0.999
    np.testing.assert_allclose(loud.beats, quiet.beats)
    assert quiet.tempo_bpm == pytest.approx(loud.tempo_bpm)


def test_features_have_the_promised_shapes(
    analysed: dict[str, tuple[DemoSong, MusicFeatures]],
) -> None:
    song, features = analysed["groove"]
    n_frames = int(np.ceil(song.duration * 60))
    assert features.fps == 60.0 and features.n_bands == 56
    assert features.duration == pytest.approx(song.duration)
    assert features.band_edges_hz.shape == (57,) and features.band_centres_hz.shape == (56,)
    for name, dtype in [
        ("levels", np.float32),
        ("onset", np.float32),
        ("triggers", np.bool_),
        ("activation", np.float32),
    ]:
        array = getattr(features, name)
        assert array.shape == (n_frames, 56) and array.dtype == dtype, name
    assert features.beat_phase.shape == (n_frames,) and features.beat_phase.dtype == np.float32
    assert np.all((features.beat_phase >= 0) & (features.beat_phase < 1))
    assert features.beats.dtype == np.float64 and np.all(np.diff(features.beats) > 0)
    assert features.levels.min() >= -80.0 and features.levels.max() < 10.0
    assert np.all(features.onset >= 0)
    assert len(features.song_hash) == 64


def test_activation_jumps_to_one_and_decays(
    analysed: dict[str, tuple[DemoSong, MusicFeatures]],
) -> None:
    _, features = analysed["groove"]
    np.testing.assert_array_equal(features.activation[features.triggers], 1.0)
    band = int(np.argmax(features.triggers.sum(axis=0)))
    fired = np.flatnonzero(features.triggers[:, band])
    gap = np.flatnonzero(np.diff(fired) > 3)[0]
    after = features.activation[fired[gap] : fired[gap + 1], band]
    assert np.all(np.diff(after) < 0) and np.all((after > 0) & (after <= 1))


def test_beat_phase_is_zero_on_beats(analysed: dict[str, tuple[DemoSong, MusicFeatures]]) -> None:
    _, features = analysed["sway"]
    frames = np.round(features.beats * features.fps).astype(int)
    frames = frames[frames < features.n_frames]
    phase = features.beat_phase[frames]
    wrapped = np.minimum(phase, 1.0 - phase)
    assert np.max(wrapped) < 0.05


def test_bpm_override(groove: DemoSong, groove_audio: Audio) -> None:
    features = analyse(groove_audio, bpm=60.0)  # e.g. a listener counting half time
    assert features.tempo_bpm == 60.0
    assert np.median(np.diff(features.beats)) == pytest.approx(1.0, rel=0.02)
    assert f_measure(features.beats, groove.beats, BEAT_TOLERANCE_S) == pytest.approx(
        2 / 3, abs=0.02
    )


def test_other_frame_rates_band_counts_and_sample_rates(groove_audio: Audio) -> None:
    excerpt = groove_audio.samples[: 20 * groove_audio.sample_rate]
    at_48k = scipy.signal.resample_poly(excerpt, 160, 147).astype(np.float32)
    features = analyse(Audio(at_48k, 48000), fps=30.0, n_bands=48)
    assert features.levels.shape == (600, 48)
    assert features.tempo_bpm == pytest.approx(120.0, rel=0.01)


def test_silence_gives_no_triggers_and_no_beats() -> None:
    features = analyse(Audio(np.zeros(5 * 44100, np.float32), 44100))
    assert not features.triggers.any()
    assert not features.activation.any()
    assert len(features.beats) == 0 and features.tempo_bpm == 0.0
    assert np.all(features.levels == -80.0)
    assert not features.beat_phase.any()


def test_faint_noise_counts_as_silence() -> None:
    rng = np.random.default_rng(3)
    hiss = (1e-5 * rng.standard_normal(5 * 44100)).astype(np.float32)  # -100 dBFS
    assert not analyse(Audio(hiss, 44100)).triggers.any()


def test_analysis_is_deterministic(groove_audio: Audio) -> None:
    excerpt = Audio(groove_audio.samples[: 10 * 44100], 44100)
    first, second = analyse(excerpt), analyse(excerpt)
    for name in ("levels", "onset", "triggers", "activation", "beats", "beat_phase"):
        np.testing.assert_array_equal(getattr(first, name), getattr(second, name))
    assert first.song_hash == second.song_hash


@pytest.mark.parametrize(
    ("kwargs", "message"), [({"fps": 0.0}, "fps"), ({"bpm": -1.0}, "bpm"), ({"n_bands": 70}, "48")]
)
def test_bad_settings(tone: Audio, kwargs: dict[str, float], message: str) -> None:
    with pytest.raises(ValueError, match=message):
        analyse(tone, **kwargs)  # type: ignore[arg-type]
