"""Dance responders (seed 000, "Species of Dance Responders", Fig. 5–6).

Each node has two responder slots of five genes: species bucket (the lowest
`NONE_BELOW` of the range is "none"), force strength, pitch, pitch width and
one custom value. A responder listens to the contiguous band range its pitch
and width select and, when that band's trigger fires, applies its species'
force to its node, scaled by its strength and the band's decaying activation.
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
from sinews.music.spectrum import band_for_pitch
from sinews.springmass.actuators import ActuatorKind

__all__ = ["NONE_BELOW", "REACTION_FRAMES", "SPECIES", "Responder", "delayed", "responders"]

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
"""Frames (at 60 fps: 67 ms) between a band's trigger and its responders' move.

Like a dancer's reaction to a sound it hears (dancer.js itself answered one
1024-sample block, 23 ms, late). Measured: with no delay the body's pauses come
before the beats (each move starts on its trigger), and the beat-align score
of random dancers barely beat motion without music; 3–6 frames of reaction put
the pause on the beat and roughly double the score (docs/architecture.md).
"""

_STRENGTH = (20.0, 140.0)
"""Newtons at full activation for strength genes 0 and 1."""


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
