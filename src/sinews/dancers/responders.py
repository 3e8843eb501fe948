"""Dance responders (seed 000, "Species of Dance Responders", Fig. 5–6).

Each node has two responder slots of five genes: species bucket (the lowest
`NONE_BELOW` of the range is "none"), force strength, pitch, pitch width and
one custom value. A responder listens to the contiguous band range its pitch
and width select and, when that band's trigger fires, applies its species'
force to its node, scaled by its strength and the band's decaying activation.
With beats, moves happen on the beat grid (`beat_drive`): a band that fired near a beat
moves on that beat, and sway and shake follow a two-beat phase (docs/dancing.md).
Each species is an engine actuator (`sinews.springmass.actuators`); how the
force shows depends on the node it sits on: a heavy head on stiff springs
barely nods where a light hand on soft springs flies.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from sinews.dancers.genome import DancerGenome
from sinews.dancers.skeleton import NODES
from sinews.music.features import MusicFeatures
from sinews.music.spectrum import band_for_pitch
from sinews.springmass.actuators import ActuatorKind

__all__ = [
    "BEAT_WINDOW",
    "MOVE_DECAY_BEATS",
    "MOVE_LEAD_FRAMES",
    "MOVE_RISE_FRAMES",
    "NONE_BELOW",
    "PHASE_LEAD_FRAMES",
    "REACTION_FRAMES",
    "SPECIES",
    "Responder",
    "beat_drive",
    "delayed",
    "responders",
    "two_beat_phase",
]

SPECIES: dict[str, ActuatorKind] = {
    "kick": ActuatorKind.PUSH,
    "bounce": ActuatorKind.BOB,
    "spin": ActuatorKind.SPIN,
    "reach": ActuatorKind.REACH,
    "shake": ActuatorKind.SHAKE,
    "sway": ActuatorKind.SWAY,
    "pulse": ActuatorKind.PULSE,
}
"""Species names and the force pattern each one applies (see `ActuatorKind`)."""

NONE_BELOW = 0.55
"""Species genes below this mean the slot is empty (about 15 of 34 slots are filled)."""

REACTION_FRAMES = 4
"""Frames (at 60 fps: 67 ms) between a band's trigger and its responders' move, for a
song without beats (with beats, moves follow the beat grid: `beat_drive`).

Like a dancer's reaction to a sound it hears (dancer.js itself answered one
1024-sample block, 23 ms, late). Measured: with no delay the body's pauses come
before the beats (each move starts on its trigger), and the beat-align score
of random dancers barely beat motion without music; 3–6 frames of reaction put
the pause on the beat and roughly double the score (docs/architecture.md).
"""

_STRENGTH = (8.0, 50.0)
"""Newtons at full drive for strength genes 0 and 1, on a 1 kg node (see
`sinews.dancers.develop.RESPONDER_MASS_POWER`). Was 20–140 N: springs stretched past
1.5× in 75 % of frames."""


@dataclass(frozen=True)
class Responder:
    """One filled responder slot.

    Attributes:
        node: index into `NODES` of the node it sits on.
        slot: 0 or 1.
        species: a key of `SPECIES`.
        strength: newtons at full activation.
        bands: (first, last) band indices it listens to, inclusive.
        custom: the species' tuning value in [0, 1].
    """

    node: int
    slot: int
    species: str
    strength: float
    bands: tuple[int, int]
    custom: float

    @property
    def node_name(self) -> str:
        """Name of the node it sits on."""
        return NODES[self.node]


def _species(gene: float) -> str | None:
    if gene < NONE_BELOW:
        return None
    names = list(SPECIES)
    index = int((gene - NONE_BELOW) / (1.0 - NONE_BELOW) * len(names))
    return names[min(index, len(names) - 1)]


def responders(genome: DancerGenome, n_bands: int) -> list[Responder]:
    """The filled responder slots of ``genome``, for a song analysed into ``n_bands`` bands."""
    found = []
    for node, slots in enumerate(genome.responders):
        for slot, (species_gene, strength, pitch, width, custom) in enumerate(slots):
            species = _species(float(species_gene))
            if species is None:
                continue
            lo, hi = band_for_pitch(float(pitch), float(width), n_bands)
            newtons = float(np.interp(strength, (0.0, 1.0), _STRENGTH))
            found.append(Responder(node, slot, species, newtons, (lo, hi - 1), float(custom)))
    return found


def delayed(
    table: npt.NDArray[np.float32], frames: int = REACTION_FRAMES
) -> npt.NDArray[np.float32]:
    """``table`` (T, ...) shifted ``frames`` rows later, zeros first (what responders feel)."""
    pad = np.zeros((frames, *table.shape[1:]), dtype=table.dtype)
    return np.concatenate([pad, table])


BEAT_WINDOW = 0.25
"""A band that fires within this fraction of a beat of a beat moves its responders on that beat."""

MOVE_DECAY_BEATS = 0.35
"""Time constant of a move's force, in beats: it is spent well before the next beat."""

MOVE_RISE_FRAMES = 0
"""Frames over which a move's force eases in (smoothstep) instead of jumping to full."""

MOVE_LEAD_FRAMES = 6
"""Frames between a beat and the start of the moves it carries (negative: before it)."""

PHASE_LEAD_FRAMES = 0
"""Frames the sway / shake phase runs ahead of the beat grid (to let the body's lag land
its turning points on the beats)."""


def two_beat_phase(
    beats: npt.NDArray[np.float64], n_frames: int, fps: float, bpm: float
) -> npt.NDArray[np.float32]:
    """(T,) phase in [0, 1) over two beats: 0 on every other beat, 0.5 on the ones between.

    Linear between tracked beats, continued at the tempo's period outside them; all zero
    without beats.
    """
    if len(beats) == 0 or not bpm > 0:
        return np.zeros(n_frames, dtype=np.float32)
    times = np.arange(n_frames) / fps
    period = 60.0 / bpm
    index = np.searchsorted(beats, times, side="right") - 1
    count = np.empty(n_frames)
    inside = (index >= 0) & (index < len(beats) - 1)
    i = index[inside]
    count[inside] = i + (times[inside] - beats[i]) / (beats[i + 1] - beats[i])
    before = index < 0
    count[before] = (times[before] - beats[0]) / period
    after = index >= len(beats) - 1
    count[after] = len(beats) - 1 + (times[after] - beats[-1]) / period
    phase = np.mod(count / 2.0, 1.0).astype(np.float32)
    phase[phase >= 1.0] = 0.0
    return phase


def beat_drive(
    music: MusicFeatures, n_frames: int | None = None
) -> tuple[npt.NDArray[np.float32], npt.NDArray[np.float32]]:
    """What responders feel: band moves on the beat grid, and the two-beat phase.

    A band carries a move on a beat when it fired within `BEAT_WINDOW` of a beat of
    that beat (so off-beat hi-hats, fired on every eighth, still give one move a beat,
    on the beat). The move's drive jumps to 1 `MOVE_LEAD_FRAMES` after the beat and
    decays with a time constant of `MOVE_DECAY_BEATS` beats, so the body hits the beat
    and settles before the next. A song without beats falls back to the band
    activation `REACTION_FRAMES` late.

    Args:
        music: the analysed song.
        n_frames: frames to cover (default: the song's).

    Returns:
        drive (T, B) float32 in [0, 1] and phase (T,) float32 in [0, 1).
    """
    n = music.n_frames if n_frames is None else n_frames
    fps = music.fps
    beats = np.asarray(music.beats, dtype=np.float64)
    if len(beats) < 2 or not music.tempo_bpm > 0:
        drive = delayed(music.activation)[:n]
        phase = delayed(music.beat_phase)[:n]
        pad = n - len(drive)
        if pad > 0:
            drive = np.concatenate([drive, np.zeros((pad, drive.shape[1]), np.float32)])
            phase = np.concatenate([phase, np.zeros(pad, np.float32)])
        return drive, phase
    drive = np.zeros((n, music.n_bands), dtype=np.float32)
    intervals = np.diff(beats)
    intervals = np.append(intervals, intervals[-1])
    triggers = music.triggers
    for beat, interval in zip(beats.tolist(), intervals.tolist(), strict=True):
        lo = max(0, int(np.ceil((beat - BEAT_WINDOW * interval) * fps)))
        hi = min(len(triggers), int(np.floor((beat + BEAT_WINDOW * interval) * fps)) + 1)
        if hi <= lo:
            continue
        fired = triggers[lo:hi].any(axis=0)
        if not fired.any():
            continue
        start = round(beat * fps) + MOVE_LEAD_FRAMES
        length = round(2.0 * interval * fps)
        first, last = max(start, 0), min(start + length, n)
        if last <= first:
            continue
        elapsed = (np.arange(first, last) - start) / fps
        envelope = np.exp(-elapsed / (MOVE_DECAY_BEATS * interval))
        if MOVE_RISE_FRAMES > 0:
            rise = np.clip(elapsed * fps / MOVE_RISE_FRAMES, 0.0, 1.0)
            envelope *= rise * rise * (3.0 - 2.0 * rise)
        envelope = envelope.astype(np.float32)
        block = drive[first:last, fired]
        np.maximum(block, envelope[:, None], out=block)
        drive[first:last, fired] = block
    phase = two_beat_phase(beats + PHASE_LEAD_FRAMES / fps * -1.0, n, fps, music.tempo_bpm)
    return drive, phase
