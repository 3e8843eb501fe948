"""The groove: a whole-body move on the beat grid that every dancer makes (docs/dancing.md).

Responders push single nodes; pushed hard, a node stretches its short springs before the
body follows. The groove instead moves the home targets of the whole body together (the
engine's pose signals, `Body.pose_basis`), so the springs carry the body along near
their rest lengths:

- **sway**: the body leans to one side on one beat and to the other on the next (two
  signals' worth of phase, `two_beat_phase`); its turning points, where the body pauses,
  are the beats. Sideways moves are zero-mean over the nodes, so the centroid-following
  home does not drift with them.
- **bounce**: the hips and everything above them dip at each turning point (on the beat)
  and rise while the body crosses the middle; the knees take half the dip.

How far comes from existing body genes, so every genome keeps its meaning: the less
grounded a dancer, the wider its sway (groundedness); the wider its stance, the deeper
its bounce (stance); torso triangularity trades a lean from the feet (broad shoulders:
the head moves most) for a hip sway (wide hips: the pelvis moves most, the head less).
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from sinews.dancers.responders import two_beat_phase
from sinews.dancers.skeleton import NODES
from sinews.music.features import MusicFeatures

__all__ = ["BOUNCE", "GROOVE_LEAD", "SIGNALS", "SWAY", "groove_basis", "groove_signals"]

SIGNALS = ("sway", "bounce")
"""The pose signals, in the order of the basis's K axis."""

SWAY = (0.50, 0.25)
"""Sideways reach of the sway (metres, at the top of the body) at groundedness genes 0 and 1."""

BOUNCE = (0.03, 0.09)
"""Depth of the bounce (metres, at the hips) at stance genes 0 and 1."""

GROOVE_LEAD = 0.06
"""Seconds the groove's signals run ahead of the beats, so that the body, which follows
its home targets with a lag, turns on the beat (0, 0.06, 0.12 s gave lift 0.42, 0.64,
0.51 on two tuning songs)."""


def _lerp(lo: float, hi: float, t: float) -> float:
    return lo + (hi - lo) * t


def groove_basis(rest: npt.NDArray[np.float64], body: dict[str, float]) -> npt.NDArray[np.float64]:
    """(N, 2, 2) home-target metres per unit of sway and bounce for a body standing at ``rest``.

    Args:
        rest: (N, 2) rest pose, nodes in `NODES` order, feet on the floor.
        body: the genome's main body modifiers (`DancerGenome.body`).
    """
    y = rest[:, 1] - rest[:, 1].min()
    top = float(y.max())
    hip = float(y[NODES.index("l_hip")] + y[NODES.index("r_hip")]) / 2.0
    lean = y / top
    above = np.clip((y - hip) / (top - hip), 0.0, 1.0)
    hips = np.clip(y / hip, 0.0, 1.0) * (1.0 - 0.6 * above)
    tri = body["torso_triangularity"]
    profile = tri * lean + (1.0 - tri) * hips / float(hips.max())
    basis = np.zeros((len(rest), len(SIGNALS), 2))
    basis[:, 0, 0] = _lerp(*SWAY, body["groundedness"]) * profile
    basis[:, 0, 0] -= basis[:, 0, 0].mean()
    basis[:, 1, 1] = -_lerp(*BOUNCE, body["stance"]) * np.clip(y / hip, 0.0, 1.0)
    return basis


def groove_signals(music: MusicFeatures, n_frames: int | None = None) -> npt.NDArray[np.float32]:
    """(T, 2) the sway and bounce signals of ``music`` (zeros for a song without beats).

    Sway is cos(2 pi phase) over the two-beat phase, +1 and -1 on alternate beats; bounce
    is its square (1 on every beat, 0 between). Both fade in over the beat before the
    first tracked beat and out over the beat after the last, so nothing moves over a
    silent intro or outro.
    """
    n = music.n_frames if n_frames is None else n_frames
    beats = np.asarray(music.beats, dtype=np.float64)
    if len(beats) < 2 or not music.tempo_bpm > 0:
        return np.zeros((n, len(SIGNALS)), dtype=np.float32)
    phase = two_beat_phase(beats - GROOVE_LEAD, n, music.fps, music.tempo_bpm)
    sway = np.cos(2.0 * np.pi * phase.astype(np.float64))
    period = 60.0 / music.tempo_bpm
    times = np.arange(n) / music.fps + GROOVE_LEAD
    fade = np.clip((times - beats[0]) / period + 1.0, 0.0, 1.0)
    fade *= np.clip((beats[-1] - times) / period + 1.0, 0.0, 1.0)
    fade = fade * fade * (3.0 - 2.0 * fade)
    return np.stack([sway * fade, sway * sway * fade], axis=1).astype(np.float32)
