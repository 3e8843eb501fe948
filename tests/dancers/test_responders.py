"""Dance responders: genes to species and bands, and dances that follow the music."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from sinews.dancers import NODES, DancerGenome, develop
from sinews.dancers.genome import RESPONDER_GENES
from sinews.dancers.responders import NONE_BELOW, SPECIES, responders
from sinews.experiments.dancers.simulate import dance
from sinews.music.features import MusicFeatures
from sinews.music.spectrum import band_edges, band_for_pitch

N_BANDS = 56


def genome_with(slots: dict[tuple[str, int], dict[str, float]]) -> DancerGenome:
    """The neutral dancer with the given responder slots filled."""
    values = DancerGenome.neutral().values.copy()
    start = DancerGenome.SIZE - len(NODES) * 2 * len(RESPONDER_GENES)
    for (node, slot), genes in slots.items():
        at = start + (NODES.index(node) * 2 + slot) * len(RESPONDER_GENES)
        for k, name in enumerate(RESPONDER_GENES):
            values[at + k] = genes.get(name, 0.5)
    return DancerGenome(values)


def species_gene(name: str) -> float:
    index = list(SPECIES).index(name)
    return NONE_BELOW + (index + 0.5) / len(SPECIES) * (1 - NONE_BELOW)


def fake_music(active_bands: list[int], frames: int = 600, every: int = 30) -> MusicFeatures:
    """A song whose only sound is a hit every ``every`` frames in ``active_bands``."""
    triggers = np.zeros((frames, N_BANDS), dtype=bool)
    triggers[::every, active_bands] = True
    since = np.arange(frames) % every
    activation = np.zeros((frames, N_BANDS), dtype=np.float32)
    activation[:, active_bands] = np.exp(-since / 6.0)[:, None]
    edges = band_edges(N_BANDS)
    return MusicFeatures(
        fps=60.0, duration=frames / 60.0, band_edges_hz=edges,
        band_centres_hz=np.sqrt(edges[:-1] * edges[1:]),
        levels=np.zeros((frames, N_BANDS), np.float32),
        onset=np.zeros((frames, N_BANDS), np.float32),
        triggers=triggers, activation=activation, tempo_bpm=120.0,
        beats=np.arange(0, frames, every) / 60.0,
        beat_phase=(since / every).astype(np.float32), song_hash="test",
    )  # fmt: skip


def test_species_buckets_cover_none_and_every_species() -> None:
    assert responders(DancerGenome.neutral(), N_BANDS) == []
    for name in SPECIES:
        genome = genome_with({("r_hand", 1): {"species": species_gene(name)}})
        (found,) = responders(genome, N_BANDS)
        assert found.species == name and found.node_name == "r_hand" and found.slot == 1
    genome = genome_with({("head", 0): {"species": NONE_BELOW - 0.01}})
    assert responders(genome, N_BANDS) == []


def test_pitch_genes_pick_the_band_range() -> None:
    genes = {"species": species_gene("kick"), "pitch": 0.8, "width": 0.3}
    (found,) = responders(genome_with({("l_foot", 0): genes}), N_BANDS)
    lo, hi = band_for_pitch(0.8, 0.3, N_BANDS)
    assert found.bands == (lo, hi - 1)
    body = develop(genome_with({("l_foot", 0): genes}), n_bands=N_BANDS)
    assert body.n_actuators == 1 and tuple(body.actuator_channels[0]) == (lo, hi - 1)


def test_random_genomes_carry_a_handful_of_responders() -> None:
    rng = np.random.default_rng(0)
    counts = [len(responders(DancerGenome.random(rng), N_BANDS)) for _ in range(200)]
    assert 10 < np.mean(counts) < 20


def test_a_responder_ignores_music_outside_its_bands() -> None:
    genes = {"species": species_gene("kick"), "pitch": 0.1, "width": 0.0, "strength": 1.0}
    genome = genome_with({("r_hand", 0): genes})
    (lo, _), other = band_for_pitch(0.1, 0.0, N_BANDS), N_BANDS - 1
    # the same body without the responder still grooves to the beats (sinews.dancers.groove)
    (groove_only,) = dance([DancerGenome.neutral()], 10.0, music=fake_music([other]))
    elsewhere = dance([genome], 10.0, music=fake_music([other]))[0]
    np.testing.assert_array_equal(groove_only.positions, elsewhere.positions)
    assert elsewhere.triggers is not None and not elsewhere.triggers.any()
    heard = dance([genome], 10.0, music=fake_music([lo]))[0]
    assert np.abs(heard.positions - groove_only.positions).max() > 0.05
    assert heard.triggers is not None and heard.triggers[:600:30, 0].all()
    assert heard.trigger_nodes is not None
    assert list(heard.trigger_nodes) == [NODES.index("r_hand")]


def test_species_move_a_hand_in_different_ways() -> None:
    music = fake_music(list(range(N_BANDS)))
    paths = {}
    for name in SPECIES:
        genes = {"species": species_gene(name), "strength": 1.0, "custom": 0.7}
        (traj,) = dance([genome_with({("r_hand", 0): genes})], 10.0, music=music)
        hand = traj.positions[:, NODES.index("r_hand")].astype(np.float64)
        paths[name] = hand - hand.mean(axis=0)
    names = list(paths)
    for i, a in enumerate(names):
        assert np.abs(paths[a]).max() > 0.02, f"{a} hardly moves the hand"
        for b in names[i + 1 :]:
            scale = max(np.abs(paths[a]).max(), np.abs(paths[b]).max())
            assert np.abs(paths[a] - paths[b]).max() > 0.3 * scale, f"{a} looks like {b}"


def test_the_same_force_shows_differently_on_a_head_and_a_hand() -> None:
    music = fake_music(list(range(N_BANDS)))
    genes = {"species": species_gene("kick"), "strength": 1.0, "custom": 0.0}
    moved = {}
    (groove_only,) = dance([DancerGenome.neutral()], 5.0, music=music)
    for node in ("head", "r_hand"):
        (traj,) = dance([genome_with({(node, 0): genes})], 5.0, music=music)
        k = NODES.index(node)
        moved[node] = np.ptp(traj.positions[:, k, 0] - groove_only.positions[:, k, 0])
    assert moved["r_hand"] > 2 * moved["head"]


def test_responders_off_removes_every_actuator() -> None:
    genome = DancerGenome.random(np.random.default_rng(5))
    music = fake_music(list(range(N_BANDS)))
    with_music = dance([genome], 5.0, music=music, responders=False)[0]
    without = dance([genome], 5.0)[0]
    np.testing.assert_array_equal(with_music.positions, without.positions)
    assert with_music.triggers is not None and with_music.triggers.shape[1] == 0


def test_dance_needs_a_length_or_a_song() -> None:
    with pytest.raises(Exception, match="seconds or a song"):
        dance([DancerGenome.neutral()])
    body = develop(DancerGenome.neutral())
    assert dataclasses.replace(body).n_actuators == 0
