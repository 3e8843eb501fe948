"""Entrained spring nets: the music pushes chosen masses, so a net can lock to the beat.

A dancing net's genes are the net's (`SpringNetEncoding`) followed by one drive weight
per mass and `DRIVE` column, each gene u in [0, 1] a weight ``(2u − 1) · drive`` (the
run's largest drive weight, `DRIVE_FORCE` unless set).
Every tick mass i feels ``f_i = Σ_d w_id · music_d`` (the net's input forces, seed 001's
"applying forces to the point masses"), read from the song's `MUSIC_TERMINALS` after
the figure's sensors (`MusicInput`). The fitness is the figure's dance (`DANCE_FIGURES`,
e.g. `luxo_dance`): beat lift plus style.

`dominant_period` measures what the issue asks of an entrained net: the period of the
strongest component of its output masses' motion, to compare with the beat period.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from sinews.control.music_input import MUSIC_TERMINALS

__all__ = [
    "DANCE_FIGURES", "DRIVE", "DRIVE_FORCE", "MAX_DRIVE_FORCE", "dominant_period", "drive_weights",
]  # fmt: skip

FloatArray = npt.NDArray[np.float64]

DRIVE = ("beat_sin", "beat_cos")
"""The music columns that push the masses: the beat's phase, which averages to zero over
a beat. (A band level would too, but its mean is a constant push that sends the free net
accelerating away: measured, an evolved net with a bass drive drifted off on 5 of 6
songs.)"""
DRIVE_FORCE = 30.0
"""The largest drive weight (force per unit of music) unless a run sets its own."""
MAX_DRIVE_FORCE = 1000.0
"""The largest a run may set."""
DANCE_FIGURES = {"luxo": "luxo-dance", "snake": "snake-dance", "humanoid": "humanoid-dance"}
"""Figures whose spring nets can dance, and their dance task (its joints are the ones the
nets drive; the others hold their neutral angles)."""


def drive_weights(
    genes: FloatArray, n_masses: int, n_sensors: int, force: float = DRIVE_FORCE
) -> FloatArray:
    """(P, n, S + M) input weights from (P, n · len(DRIVE)) drive genes in [0, 1], each
    in [-force, force].

    Zero on the S sensor columns and on the music columns outside `DRIVE`.
    """
    weights = np.zeros((len(genes), n_masses, n_sensors + len(MUSIC_TERMINALS)))
    drive = (2.0 * np.asarray(genes, dtype=np.float64) - 1.0) * force
    columns = [n_sensors + MUSIC_TERMINALS.index(name) for name in DRIVE]
    weights[:, :, columns] = drive.reshape(len(genes), n_masses, len(DRIVE))
    return weights


def dominant_period(signal: npt.ArrayLike, hz: float, *, skip: float = 1.0) -> float:
    """The period (s) of the strongest non-zero frequency of ``signal`` after ``skip`` s.

    The straight line that fits each signal best is taken away first: a net pushed by a
    force whose mean over the trial is not zero drifts, and the drift is not a swing.

    Args:
        signal: (T,) or (T, K) samples at ``hz`` (K signals: their power spectra summed).
        hz: samples per second.
        skip: seconds of transient left out.

    Returns:
        The period, s; inf for a signal that is constant (or a straight line).
    """
    x = np.asarray(signal, dtype=np.float64)
    x = x.reshape(len(x), -1)[round(skip * hz) :]
    t = np.linspace(-1.0, 1.0, len(x))
    line = np.polynomial.polynomial.polyfit(t, x, 1)
    x = (x - np.polynomial.polynomial.polyval(t, line).T) * np.hanning(len(x))[:, None]
    pad = 8 * len(x)  # a finer grid of frequencies
    power = (np.abs(np.fft.rfft(x, n=pad, axis=0)) ** 2).sum(axis=1)
    power[0] = 0.0
    peak = int(np.argmax(power))
    still = np.abs(x).max(initial=0.0) < 1e-12  # nothing but rounding left
    return float("inf") if still or power[peak] <= 0.0 else pad / (peak * hz)
