"""Decoding real audio files of every supported format, and every way a file can be bad."""

from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest
import soundfile as sf

from sinews.ffmpeg import FFMPEG_ENV, find_ffmpeg
from sinews.music import MAX_SECONDS, Audio, AudioError, load_audio, save_wav

SR = 44100


def _stereo(seconds: float = 2.0, sr: int = SR) -> np.ndarray:
    """A 440 Hz tone on the left and a 660 Hz tone on the right, at 0.4."""
    t = np.arange(round(seconds * sr)) / sr
    return 0.4 * np.stack([np.sin(2 * np.pi * 440 * t), np.sin(2 * np.pi * 660 * t)], axis=1)


def _assert_audio_error(path: Path, excinfo: pytest.ExceptionInfo[AudioError], *words: str) -> None:
    message = str(excinfo.value)
    assert message.startswith(str(path)), message
    assert "\n" not in message and "Traceback" not in message
    for word in words:
        assert word in message, message


@pytest.mark.parametrize("suffix", [".wav", ".flac", ".ogg", ".mp3"])
def test_each_format_decodes_to_a_mono_mixdown_at_its_rate(tmp_path: Path, suffix: str) -> None:
    stereo = _stereo()
    path = save_wav(tmp_path / f"tone{suffix}", stereo, SR)
    audio = load_audio(path)
    assert audio.sample_rate == SR
    assert audio.samples.dtype == np.float32 and audio.samples.ndim == 1
    assert abs(audio.duration - 2.0) < 0.06  # lossy codecs may pad a frame
    expected = stereo.mean(axis=1)
    if suffix in (".wav", ".flac"):
        np.testing.assert_allclose(audio.samples, expected, atol=1e-4)
    else:  # lossy: compare loudness, not samples
        rms = np.sqrt(np.mean(audio.samples**2))
        assert rms == pytest.approx(np.sqrt(np.mean(expected**2)), rel=0.1)


def test_opus_comes_back_at_48_khz(tmp_path: Path) -> None:
    path = save_wav(tmp_path / "tone.opus", _stereo(sr=48000), 48000)
    audio = load_audio(path)
    assert audio.sample_rate == 48000
    assert abs(audio.duration - 2.0) < 0.05


def test_long_ogg_is_written_block_by_block(tmp_path: Path) -> None:
    rng = np.random.default_rng(0)
    noise = 0.1 * rng.standard_normal((60 * SR, 2))
    audio = load_audio(save_wav(tmp_path / "long.ogg", noise, SR))
    assert abs(audio.duration - 60.0) < 0.05


def test_content_wins_over_the_extension(tmp_path: Path) -> None:
    wav = save_wav(tmp_path / "tone.wav", _stereo(), SR)
    flac = save_wav(tmp_path / "tone.flac", _stereo(), SR)
    wav_named_mp3 = tmp_path / "really_a_wav.mp3"
    flac_named_wav = tmp_path / "really_a_flac.wav"
    shutil.copy(wav, wav_named_mp3)
    shutil.copy(flac, flac_named_wav)
    assert load_audio(wav_named_mp3).duration == pytest.approx(2.0)
    assert load_audio(flac_named_wav).duration == pytest.approx(2.0)


def test_silence_is_a_song(tmp_path: Path) -> None:
    path = save_wav(tmp_path / "silence.wav", np.zeros(3 * SR), SR)
    audio = load_audio(path)
    assert audio.duration == pytest.approx(3.0)
    assert not np.any(audio.samples)


needs_ffmpeg = pytest.mark.skipif(find_ffmpeg() is None, reason="no ffmpeg available")


def _m4a(tmp_path: Path) -> Path:
    exe = find_ffmpeg()
    assert exe is not None
    wav = save_wav(tmp_path / "tone.wav", _stereo(), SR)
    m4a = tmp_path / "tone.m4a"
    command = [exe, "-hide_banner", "-loglevel", "error", "-i", str(wav), "-c:a", "aac", str(m4a)]
    subprocess.run(command, check=True)
    return m4a


@needs_ffmpeg
def test_m4a_decodes_through_ffmpeg(tmp_path: Path) -> None:
    audio = load_audio(_m4a(tmp_path))
    assert audio.sample_rate == SR
    assert abs(audio.duration - 2.0) < 0.05
    rms = np.sqrt(np.mean(audio.samples**2))
    assert rms == pytest.approx(np.sqrt(np.mean(_stereo().mean(axis=1) ** 2)), rel=0.1)


@needs_ffmpeg
def test_m4a_without_ffmpeg_says_how_to_convert(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    path = _m4a(tmp_path)
    monkeypatch.setenv(FFMPEG_ENV, "off")
    with pytest.raises(AudioError) as excinfo:
        load_audio(path)
    _assert_audio_error(path, excinfo, "no ffmpeg", "convert it to WAV")


def test_text_file_named_wav(tmp_path: Path) -> None:
    path = tmp_path / "notes.wav"
    path.write_text("these are not the samples you are looking for\n" * 20)
    with pytest.raises(AudioError) as excinfo:
        load_audio(path)
    _assert_audio_error(path, excinfo, "not an audio file")


def test_empty_file(tmp_path: Path) -> None:
    path = tmp_path / "empty.mp3"
    path.touch()
    with pytest.raises(AudioError) as excinfo:
        load_audio(path)
    _assert_audio_error(path, excinfo, "empty")


@pytest.mark.parametrize("suffix", [".wav", ".mp3"])
def test_truncated_file(tmp_path: Path, suffix: str) -> None:
    whole = save_wav(tmp_path / f"whole{suffix}", _stereo(4.0), SR).read_bytes()
    path = tmp_path / f"cut{suffix}"
    path.write_bytes(whole[: len(whole) // 2])
    with pytest.raises(AudioError) as excinfo:
        load_audio(path)
    _assert_audio_error(path, excinfo, "truncated")


@pytest.mark.parametrize("suffix", [".wav", ".flac", ".ogg"])
def test_file_cut_after_its_header(tmp_path: Path, suffix: str) -> None:
    whole = save_wav(tmp_path / f"whole{suffix}", _stereo(), SR).read_bytes()
    path = tmp_path / f"header_only{suffix}"
    path.write_bytes(whole[:100])
    with pytest.raises(AudioError) as excinfo:
        load_audio(path)
    _assert_audio_error(path, excinfo)


@pytest.mark.parametrize("suffix", [".flac", ".ogg"])
def test_corrupt_file(tmp_path: Path, suffix: str) -> None:
    data = bytearray(save_wav(tmp_path / f"whole{suffix}", _stereo(), SR).read_bytes())
    rng = np.random.default_rng(7)
    for position in rng.integers(64, len(data), 300):
        data[position] = int(rng.integers(0, 256))
    path = tmp_path / f"corrupt{suffix}"
    path.write_bytes(bytes(data))
    with pytest.raises(AudioError) as excinfo:
        load_audio(path)
    _assert_audio_error(path, excinfo, "corrupt")


def test_nan_samples_are_corrupt(tmp_path: Path) -> None:
    samples = _stereo()[:, 0].astype(np.float32)
    samples[1000] = np.nan
    path = tmp_path / "nan.wav"
    sf.write(path, samples, SR, subtype="FLOAT")
    with pytest.raises(AudioError) as excinfo:
        load_audio(path)
    _assert_audio_error(path, excinfo, "NaN")


def test_too_short(tmp_path: Path) -> None:
    path = save_wav(tmp_path / "blip.wav", _stereo(0.3), SR)
    with pytest.raises(AudioError) as excinfo:
        load_audio(path)
    _assert_audio_error(path, excinfo, "too short", "0.30 s")


def test_too_long_is_refused_from_the_header(tmp_path: Path) -> None:
    # 21 minutes at 8 kHz (the lowest rate read), 8 bits: 10 MB.
    path = tmp_path / "marathon.wav"
    sf.write(path, np.zeros(round((MAX_SECONDS + 60) * 8000), np.int16), 8000, subtype="PCM_U8")
    with pytest.raises(AudioError) as excinfo:
        load_audio(path)
    _assert_audio_error(path, excinfo, "too long", "21.0 min")


def test_writing_into_a_missing_folder_says_so(tmp_path: Path) -> None:
    with pytest.raises(AudioError, match="missing is not a directory"):
        save_wav(tmp_path / "missing" / "tone.wav", np.zeros(SR), SR)


def test_directory(tmp_path: Path) -> None:
    path = tmp_path / "album.wav"
    path.mkdir()
    with pytest.raises(AudioError) as excinfo:
        load_audio(path)
    _assert_audio_error(path, excinfo, "directory")


def test_missing_file(tmp_path: Path) -> None:
    path = tmp_path / "nowhere.flac"
    with pytest.raises(AudioError) as excinfo:
        load_audio(path)
    _assert_audio_error(path, excinfo, "no such file")


def test_fifo_is_not_a_regular_file(tmp_path: Path) -> None:
    path = tmp_path / "pipe.wav"
    os.mkfifo(path)
    with pytest.raises(AudioError) as excinfo:
        load_audio(path)
    _assert_audio_error(path, excinfo, "not a regular file")


@pytest.mark.skipif(os.geteuid() == 0, reason="root reads files whatever their mode")
def test_unreadable_file(tmp_path: Path) -> None:
    path = save_wav(tmp_path / "secret.wav", _stereo(), SR)
    path.chmod(0)
    with pytest.raises(AudioError) as excinfo:
        load_audio(path)
    _assert_audio_error(path, excinfo, "cannot read")


def test_save_wav_refuses_unknown_suffix_and_bad_samples(tmp_path: Path) -> None:
    with pytest.raises(AudioError, match=r"cannot write '\.xyz'"):
        save_wav(tmp_path / "song.xyz", _stereo(), SR)
    with pytest.raises(AudioError, match="finite"):
        save_wav(tmp_path / "song.wav", np.full(100, np.inf), SR)
    assert not list(tmp_path.iterdir())


def test_audio_duration() -> None:
    assert Audio(np.zeros(22050, np.float32), 44100).duration == 0.5
