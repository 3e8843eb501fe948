"""Beat-tracking measures (numpy only), as defined by mir_eval.beat and checked against it.

- `f_measure`: F of one-to-one matches within +-70 ms.
- `continuity`: CMLc, CMLt, AMLc, AMLt (Hainsworth / Klapuri; mir_eval's algorithm, 17.5 %
  phase and period tolerance; AML accepts the off-beat, double and half-tempo variants).
- `octave_f`: the best F over the reference, its double tempo and its two half tempi
  (the metrical level may be off by a factor 2, the phase may not).
- Both sequences drop beats before `TRIM_S` (5 s), as mir_eval's `trim_beats` does.
"""

from __future__ import annotations

import numpy as np

TRIM_S = 5.0
WINDOW_S = 0.07


def trim(beats: np.ndarray, start: float = TRIM_S) -> np.ndarray:
    beats = np.asarray(beats, dtype=np.float64)
    return beats[beats >= start]


def _matches(ref: np.ndarray, est: np.ndarray, window: float) -> int:
    """Number of one-to-one pairs within ``window``, closest pairs first."""
    if len(ref) == 0 or len(est) == 0:
        return 0
    diff = np.abs(ref[:, None] - est[None, :])
    i, j = np.nonzero(diff <= window)
    order = np.argsort(diff[i, j], kind="stable")
    used_r: set[int] = set()
    used_e: set[int] = set()
    for k in order:
        a, b = int(i[k]), int(j[k])
        if a not in used_r and b not in used_e:
            used_r.add(a)
            used_e.add(b)
    return len(used_r)


def f_measure(ref: np.ndarray, est: np.ndarray, window: float = WINDOW_S) -> float:
    if len(ref) == 0 or len(est) == 0:
        return 0.0
    hits = _matches(np.asarray(ref, float), np.asarray(est, float), window)
    if hits == 0:
        return 0.0
    precision, recall = hits / len(est), hits / len(ref)
    return 2 * precision * recall / (precision + recall)


def _offbeat(ref: np.ndarray) -> np.ndarray:
    return (ref[:-1] + ref[1:]) / 2.0


def _double(ref: np.ndarray) -> np.ndarray:
    out = np.empty(2 * len(ref) - 1)
    out[0::2] = ref
    out[1::2] = _offbeat(ref)
    return out


def variations(ref: np.ndarray) -> list[np.ndarray]:
    """The reference, its off-beat, double tempo, and the two half tempi (mir_eval's order)."""
    return [ref, _offbeat(ref), _double(ref), ref[0::2], ref[1::2]]


def octave_f(ref: np.ndarray, est: np.ndarray, window: float = WINDOW_S) -> float:
    ref = np.asarray(ref, float)
    if len(ref) < 2:
        return f_measure(ref, est, window)
    return max(f_measure(r, est, window) for r in (ref, _double(ref), ref[0::2], ref[1::2]))


def continuity(
    ref: np.ndarray, est: np.ndarray, phase_tol: float = 0.175, period_tol: float = 0.175
) -> tuple[float, float, float, float]:
    """(CMLc, CMLt, AMLc, AMLt), mir_eval.beat.continuity's algorithm."""
    ref = np.asarray(ref, float)
    est = np.asarray(est, float)
    if len(ref) < 2 or len(est) < 2:
        return 0.0, 0.0, 0.0, 0.0
    cont, total = [], []
    for r in variations(ref):
        n = max(len(r), len(est))
        used = np.zeros(n)
        success = np.zeros(n)
        for m in range(len(est)):
            d = np.abs(est[m] - r)
            near = int(np.argmin(d))
            if used[near]:
                continue
            if m == 0 or near == 0:
                ri = r[near + 1] - r[near] if near + 1 < len(r) else r[near] - r[near - 1]
                ei = est[m + 1] - est[m] if m + 1 < len(est) else est[m] - est[m - 1]
            else:
                ri = r[near] - r[near - 1]
                ei = est[m] - est[m - 1]
            if ri == 0:
                continue
            phase = abs(d[near] / ri)
            period = abs(1 - ei / ri)
            if phase < phase_tol and period < period_tol:
                used[near] = 1
                success[m] = 1
        padded = np.concatenate([[0], success, [0]])
        failures = np.flatnonzero(padded == 0)
        cont.append((np.max(np.diff(failures)) - 1) / n)
        total.append(success.sum() / n)
    return cont[0], total[0], max(cont), max(total)


def tempo_of(beats: np.ndarray) -> float:
    """BPM from the median inter-beat interval (NaN for fewer than two beats)."""
    beats = np.asarray(beats, float)
    if len(beats) < 2:
        return float("nan")
    return 60.0 / float(np.median(np.diff(beats)))


def score(ref: np.ndarray, est: np.ndarray) -> dict[str, float]:
    """F, octave-tolerant F, CMLt, AMLt and tempo ratio (est / ref) on trimmed beats."""
    r, e = trim(ref), trim(est)
    _, cmlt, _, amlt = continuity(r, e)
    return {
        "F": f_measure(r, e),
        "Foct": octave_f(r, e),
        "CMLt": cmlt,
        "AMLt": amlt,
        "ratio": tempo_of(e) / tempo_of(r),
    }
