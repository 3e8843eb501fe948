"""The groove: whole-body sway and bounce on the beat grid, springs near their rest length."""

from __future__ import annotations

import numpy as np
import pytest

from sinews.dancers import NODES, DancerGenome, develop
from sinews.dancers.groove import GROOVE_LEAD, groove_basis, groove_signals
from sinews.experiments.dancers.simulate import dance
from sinews.music.features import MusicFeatures
from sinews.music.spectrum import band_edges

N_BANDS = 56
FPS = 60.0


def beat_music(beats: np.ndarray, seconds: float = 12.0, bpm: float = 120.0) -> MusicFeatures:
    """A song with the given beats and no band sound at all."""
    frames = round(seconds * FPS)
    edges = band_edges(N_BANDS)
    zeros = np.zeros((frames, N_BANDS), np.float32)
    return MusicFeatures(
        fps=FPS, duration=seconds, band_edges_hz=edges,
        band_centres_hz=np.sqrt(edges[:-1] * edges[1:]), levels=zeros, onset=zeros,
        triggers=zeros.astype(bool), activation=zeros, tempo_bpm=bpm if len(beats) else 0.0,
        beats=beats, beat_phase=np.zeros(frames, np.float32), song_hash="test",
    )  # fmt: skip


def test_sway_turns_on_alternate_beats_and_bounce_dips_on_every_beat() -> None:
    beats = np.arange(1.0, 11.0, 0.5)
    signals = groove_signals(beat_music(beats))
    at = np.round((beats[2:-2] - GROOVE_LEAD) * FPS).astype(int)
    sway, bounce = signals[at, 0], signals[at, 1]
    np.testing.assert_allclose(np.abs(sway), 1.0, atol=0.01)
    assert np.all(np.sign(sway[1:]) == -np.sign(sway[:-1]))
    np.testing.assert_allclose(bounce, 1.0, atol=0.01)
    between = np.round((beats[2:-2] + 0.25 - GROOVE_LEAD) * FPS).astype(int)
    assert np.abs(signals[between]).max() < 0.05


def test_still_before_the_first_beat_and_without_beats() -> None:
    beats = np.arange(3.0, 11.0, 0.5)
    signals = groove_signals(beat_music(beats))
    quiet = round((3.0 - 0.5 - GROOVE_LEAD) * FPS)
    assert not signals[:quiet].any() and signals[quiet + 40 :].any()
    assert not groove_signals(beat_music(np.zeros(0))).any()


def test_basis_leaves_the_centroid_and_the_feet_in_place() -> None:
    genome = DancerGenome.neutral()
    rest = develop(genome).rest
    loose = groove_basis(rest, genome.replace(groundedness=0.0).body)
    firm = groove_basis(rest, genome.replace(groundedness=1.0).body)
    np.testing.assert_allclose(loose[:, 0, 0].mean(), 0.0, atol=1e-12)
    assert np.ptp(loose[:, 0, 0]) > 1.5 * np.ptp(firm[:, 0, 0])
    feet = [NODES.index("l_foot"), NODES.index("r_foot")]
    assert np.all(loose[feet, 1, 1] == 0.0) and loose[NODES.index("pelvis"), 1, 1] < -0.02


@pytest.mark.parametrize("triangularity", [0.0, 1.0])
def test_the_whole_body_moves_without_stretching(triangularity: float) -> None:
    genome = DancerGenome.neutral().replace(torso_triangularity=triangularity)
    body = develop(genome)
    (traj,) = dance([genome], 10.0, music=beat_music(np.arange(0.5, 10.0, 0.5)))
    p = traj.positions.astype(np.float64)
    rms = np.sqrt((np.linalg.norm(p - p.mean(axis=0), axis=2) ** 2).mean(axis=0))
    for node in ("head", "chest", "pelvis", "l_knee"):
        assert rms[NODES.index(node)] > 0.03, node
    length = np.linalg.norm(p[:, body.edges[:, 1]] - p[:, body.edges[:, 0]], axis=2)
    assert (length / body.rest_length).max() < 1.3
