"""analyse_file's on-disk cache and MusicFeatures' .npz files."""

from __future__ import annotations

import dataclasses
import hashlib
from pathlib import Path

import numpy as np
import pytest

from sinews.music import AudioError, DemoSong, MusicFeatures, analyse_file, save_wav
from sinews.music.features import ANALYSIS_VERSION


@pytest.fixture(scope="module")
def song_file(tmp_path_factory: pytest.TempPathFactory, groove: DemoSong) -> Path:
    """The first 12 s of the groove demo as FLAC."""
    path = tmp_path_factory.mktemp("songs") / "groove.flac"
    return save_wav(path, groove.samples[: 12 * groove.sample_rate], groove.sample_rate)


def _cache_files(cache: Path) -> list[Path]:
    return sorted(cache.glob("*.npz"))


def test_a_miss_writes_the_cache_and_a_hit_reads_it(song_file: Path, tmp_path: Path) -> None:
    cache = tmp_path / "cache"
    first = analyse_file(song_file, cache_dir=cache)
    (cached,) = _cache_files(cache)
    # Doctor the cached copy: if the next call returns the doctored tempo, it read the cache.
    dataclasses.replace(first, tempo_bpm=999.0).save(cached)
    second = analyse_file(song_file, cache_dir=cache)
    assert second.tempo_bpm == 999.0
    np.testing.assert_array_equal(second.levels, first.levels)
    assert _cache_files(cache) == [cached]


def test_the_song_hash_is_the_files_sha256(song_file: Path, tmp_path: Path) -> None:
    features = analyse_file(song_file, cache_dir=tmp_path)
    assert features.song_hash == hashlib.sha256(song_file.read_bytes()).hexdigest()


def test_settings_and_content_get_their_own_entries(
    song_file: Path, tmp_path: Path, groove: DemoSong
) -> None:
    cache = tmp_path / "cache"
    plain = analyse_file(song_file, cache_dir=cache)
    with_bpm = analyse_file(song_file, cache_dir=cache, bpm=60.0)
    fewer_bands = analyse_file(song_file, cache_dir=cache, n_bands=48)
    assert with_bpm.tempo_bpm == 60.0 and plain.tempo_bpm != 60.0
    assert fewer_bands.n_bands == 48
    other = save_wav(tmp_path / "other.flac", groove.samples[: 6 * 44100], 44100)
    assert analyse_file(other, cache_dir=cache).duration == pytest.approx(6.0)
    assert len(_cache_files(cache)) == 4


@pytest.mark.parametrize("garbage", [b"", b"not a zip file at all", b"PK\x03\x04broken"])
def test_a_corrupt_cache_file_is_ignored_and_rewritten(
    song_file: Path, tmp_path: Path, garbage: bytes
) -> None:
    cache = tmp_path / "cache"
    expected = analyse_file(song_file, cache_dir=cache)
    (cached,) = _cache_files(cache)
    cached.write_bytes(garbage)
    again = analyse_file(song_file, cache_dir=cache)
    np.testing.assert_array_equal(again.triggers, expected.triggers)
    np.testing.assert_array_equal(MusicFeatures.load(cached).levels, expected.levels)


def test_an_unwritable_cache_only_costs_the_reuse(song_file: Path, tmp_path: Path) -> None:
    blocked = tmp_path / "a_file_not_a_directory"
    blocked.write_text("x")
    features = analyse_file(song_file, cache_dir=blocked)
    assert features.duration == pytest.approx(12.0)


def test_analyse_file_reports_bad_files(tmp_path: Path) -> None:
    with pytest.raises(AudioError, match="no such file"):
        analyse_file(tmp_path / "missing.mp3", cache_dir=tmp_path)
    text = tmp_path / "text.wav"
    text.write_text("hello " * 100)
    with pytest.raises(AudioError, match="not an audio file"):
        analyse_file(text, cache_dir=tmp_path)


def test_save_load_round_trip(song_file: Path, tmp_path: Path) -> None:
    features = analyse_file(song_file, cache_dir=tmp_path / "cache")
    loaded = MusicFeatures.load(features.save(tmp_path / "features.npz"))
    for field in dataclasses.fields(MusicFeatures):
        a, b = getattr(features, field.name), getattr(loaded, field.name)
        if isinstance(a, np.ndarray):
            np.testing.assert_array_equal(a, b)
            assert a.dtype == b.dtype, field.name
        else:
            assert a == b, field.name
    assert not list(tmp_path.glob(".*.part*"))


def test_loading_something_else_is_an_audio_error(song_file: Path, tmp_path: Path) -> None:
    bogus = tmp_path / "bogus.npz"
    np.savez(bogus, levels=np.zeros((3, 2)))
    with pytest.raises(AudioError, match="analysis version -1"):
        MusicFeatures.load(bogus)
    np.savez(bogus, analysis_version=np.int32(ANALYSIS_VERSION), levels=np.zeros((3, 2)))
    with pytest.raises(AudioError, match="missing"):
        MusicFeatures.load(bogus)
    with pytest.raises(AudioError, match="no such file"):
        MusicFeatures.load(tmp_path / "absent.npz")
    with pytest.raises(AudioError, match="not a music-features file"):
        MusicFeatures.load(song_file)
