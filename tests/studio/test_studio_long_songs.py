"""Whole songs in the studio: danced whole up to six minutes, and a longer one's cut is named."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest

from sinews.music import save_wav
from sinews.store import RunStore
from sinews.studio.motion import Motion
from sinews.studio.runs import MAX_SECONDS, StudioRuns, cut_note
from sinews.studio.songs import SongLibrary
from studio_helpers import decode_pack, in_process_studio

RATE = 8000


def song(path: Path, seconds: float, *, beats: bool = True) -> Path:
    """A cheap mono WAV: a click every half second (120 BPM) over faint noise, or near silence."""
    rng = np.random.default_rng(1)
    samples = (0.005 * rng.standard_normal(int(seconds * RATE))).astype(np.float32)
    if beats:
        click = (0.8 * np.exp(-np.arange(400) / 60.0)).astype(np.float32)
        for k in range(0, len(samples) - len(click), RATE // 2):
            samples[k : k + len(click)] += click
    return save_wav(path, samples, RATE)


@pytest.fixture
def runs(tmp_path: Path, studio_home: None) -> Iterator[StudioRuns]:
    with RunStore(tmp_path / "studio.db") as store:
        yield StudioRuns(store, SongLibrary(tmp_path / "songs"), population=12)


def test_the_cut_is_named_only_when_there_is_one() -> None:
    assert MAX_SECONDS == 360.0
    assert cut_note(360.0, 462.4) == "dancing the first 6:00 of 7:42"
    assert cut_note(120.0, 198.0) == "dancing the first 2:00 of 3:18"
    assert cut_note(150.0, 150.0) is None
    assert cut_note(150.0, 150.3) is None  # within half a second: the whole song


def test_a_song_longer_than_two_minutes_is_danced_whole(runs: StudioRuns, tmp_path: Path) -> None:
    path = song(tmp_path / "long.wav", 150.0)
    run = runs.get(runs.create(runs.songs.import_file(path), seed=3))
    assert run.seconds == pytest.approx(150.0, abs=0.01)
    header, arrays = decode_pack(Motion(runs).generation(run.id, 0))
    assert header["frames"] / header["fps"] == pytest.approx(150.0, abs=0.1)
    assert arrays["positions"].shape[:2] == (12, header["frames"])
    # the dancers move after 2:00: the dance is not cut there and padded
    tail = arrays["positions"][:, round(125 * header["fps"]) :]
    assert np.ptp(tail, axis=1).max() > 0


def test_a_song_longer_than_six_minutes_is_cut_and_the_page_says_so(
    tmp_path: Path, studio_home: None
) -> None:
    path = song(tmp_path / "very long.wav", 370.0, beats=False)
    with in_process_studio(tmp_path / "studio.db") as client:
        with path.open("rb") as body:
            uploaded = client.post(
                "/api/songs", content=body.read(), headers={"X-Song-Name": "very long.wav"}
            )
        assert uploaded.status_code == 200, uploaded.text
        run = client.post("/api/runs", json={"song": uploaded.json()["id"]}).json()
    assert run["seconds"] == MAX_SECONDS
    assert run["duration"] == pytest.approx(370.0, abs=0.01)
    assert run["cut"] == "dancing the first 6:00 of 6:10"
