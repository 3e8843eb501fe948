"""Fit `sinews.music.beats.PHASE_WEIGHTS`: does a song's beat sit on the tracker's beats or
on their midpoints? (dev only; docs/beats.md, "The beat or the off-beat").

    .venv/bin/python benchmarks/beats/learn_phase.py [--cache DIR]

For each song of `TRAINED_ON` with reference beats: B = the tracker's beats before the phase
decision (`track` on the pooled envelope, as `analyse` runs it), O = their midpoints, and
f = `phase_evidence(B, envelopes)` for the five registers, the pooled envelope and the plain
mean. Each song gives two examples, (f, 1 if F(B) >= F(O) else 0) and (-f, the other label),
so the model has no bias and swapping B and O flips its answer. L2 logistic regression
(lambda 1, Newton steps). Prints the leave-one-set-out result (each set decided by weights
fitted on the others) and the weights fitted on all of `TRAINED_ON`.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from fetch import SETS, default_cache, excerpt_path, load_corpus  # noqa: E402
from metrics import f_measure, trim  # noqa: E402

TRAINED_ON = SETS[: SETS.index("confirm6") + 1]
"""The sets the shipped weights were fitted on; later sets stay fresh for checking them."""
L2 = 1.0
NEWTON_STEPS = 25


def examples(cache: Path) -> list[dict]:
    """Per song: its set, id, evidence f (7,) and F of B and of O against the reference."""
    from sinews.music import analyse, load_audio
    from sinews.music.beats import (
        onset_envelope,
        phase_evidence,
        register_envelopes,
        track,
    )

    _, songs = load_corpus()
    out = []
    for song in songs:
        reference = HERE / "reference" / f"{song['id']}.txt"
        if song["set"] not in TRAINED_ON or not reference.exists():
            continue
        features = analyse(load_audio(excerpt_path(cache, song["id"])))
        onset, centres, fps = features.onset, features.band_centres_hz, features.fps
        _, beats = track(onset_envelope(onset, centres), fps)
        if len(beats) < 3:
            continue
        envelopes = np.column_stack(
            [register_envelopes(onset, centres), onset_envelope(onset, centres),
             onset_envelope(onset)]
        )  # fmt: skip
        ref = trim(np.loadtxt(reference, ndmin=1))
        midpoints = (beats[:-1] + beats[1:]) / 2.0
        out.append(
            {
                "set": song["set"],
                "id": song["id"],
                "f": phase_evidence(beats, envelopes, fps),
                "F_beats": f_measure(ref, trim(beats)),
                "F_midpoints": f_measure(ref, trim(midpoints)),
            }
        )
    return out


def fit(rows: list[dict]) -> np.ndarray:
    """(7,) logistic weights from both orientations of every row."""
    x = np.array([r["f"] for r in rows] + [-r["f"] for r in rows])
    on_beats = np.array([float(r["F_beats"] >= r["F_midpoints"]) for r in rows])
    y = np.concatenate([on_beats, 1.0 - on_beats])
    w = np.zeros(x.shape[1])
    for _ in range(NEWTON_STEPS):
        p = 1.0 / (1.0 + np.exp(-(x @ w)))
        hessian = (x * (p * (1 - p))[:, None]).T @ x + L2 * np.eye(len(w))
        w -= np.linalg.solve(hessian, x.T @ (p - y) + L2 * w)
    return w


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cache", type=Path, default=default_cache())
    args = parser.parse_args()
    rows = examples(args.cache)
    print("| set | songs | F, tracker | F, with the decision | switched |")
    print("|---|---|---|---|---|")
    before_all, after_all, switched_all = [], [], []
    for held in TRAINED_ON:
        w = fit([r for r in rows if r["set"] != held])
        here = [r for r in rows if r["set"] == held]
        switch = [float(r["f"] @ w) < 0.0 for r in here]
        before = [r["F_beats"] for r in here]
        after = [r["F_midpoints"] if s else r["F_beats"] for r, s in zip(here, switch, strict=True)]
        names = [r["id"] for r, s in zip(here, switch, strict=True) if s]
        print(f"| {held} | {len(here)} | {np.mean(before):.3f} | {np.mean(after):.3f} | "
              f"{', '.join(names) or '—'} |")  # fmt: skip
        before_all += before
        after_all += after
        switched_all += names
    print(f"| all | {len(before_all)} | {np.mean(before_all):.3f} | {np.mean(after_all):.3f} | "
          f"{len(switched_all)} |")  # fmt: skip
    w = fit(rows)
    print("PHASE_WEIGHTS =", tuple(round(float(v), 4) for v in w))


if __name__ == "__main__":
    main()
