"""Score sinews' beat tracker against the corpus's reference beats, and time it.

    .venv/bin/python benchmarks/beats/evaluate.py [--set SET|all] (fetch.SETS; all: fetch.SEEN)
        [--librosa-python /work/evalvenv/bin/python] [--json OUT] [--repeats 3]

Each excerpt (see fetch.py) is decoded once with `sinews.music.load_audio`; `analyse` (the
whole per-song analysis: bands, onsets, triggers, tempo, beats) runs on it and its beats
are scored against reference/ID.txt: F (70 ms), octave-tolerant F, CMLt, AMLt (beats after
5 s, as mir_eval), and the tempo ratio ours / reference (median inter-beat intervals).
With --librosa-python, the same decoded samples go to that interpreter, which times
librosa's `onset_strength` + `beat_track` warm (after one untimed call) on them right
after ours on each song; both timings are the best of --repeats calls.

A song's phase is *contested* when two of the reference trackers agree on the tempo
(within 4 %) but not on the phase (F < 0.2 between them, reference/summary.tsv): there the
reference is one camp's choice. The summary line also gives the scores over the other songs;
the table marks contested songs with a dagger.
"""

from __future__ import annotations

import argparse
import csv
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from fetch import PAIR_COLUMNS, SETS, default_cache, excerpt_path, in_set, load_corpus  # noqa: E402
from metrics import score, tempo_of, trim  # noqa: E402

CONTESTED_F = 0.2
"""Two reference trackers at one tempo with F below this between them disagree on the phase."""
SAME_TEMPO = 0.04


def contested_songs() -> set[str]:
    """Ids of the kept songs whose phase the reference trackers disagree on."""
    with open(HERE / "reference" / "summary.tsv", newline="") as fh:
        rows = list(csv.DictReader(fh, delimiter="\t"))
    return {
        r["id"]
        for r in rows
        if r["status"] == "kept"
        and any(
            float(r[pair]) < CONTESTED_F
            and abs(float(r[f"{a}_bpm"]) / float(r[f"{b}_bpm"]) - 1.0) < SAME_TEMPO
            for pair, (a, b) in PAIR_COLUMNS.items()
        )
    }


_LIBROSA_TIMER = r"""
import sys, time
import numpy as np
import librosa
for line in sys.stdin:
    path, sr, repeats = line.split()
    y = np.load(path)
    def run():
        env = librosa.onset.onset_strength(y=y, sr=int(sr))
        return librosa.beat.beat_track(onset_envelope=env, sr=int(sr), units="time")
    run()
    best = float("inf")
    for _ in range(int(repeats)):
        t = time.perf_counter(); run(); best = min(best, time.perf_counter() - t)
    print(best, flush=True)
"""


def main() -> None:
    from sinews.music import analyse, load_audio

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cache", type=Path, default=default_cache())
    parser.add_argument("--set", default="tune", choices=(*SETS, "all"))
    parser.add_argument("--librosa-python", default=None)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--json", type=Path, default=None)
    parser.add_argument("--only", nargs="*", default=None)
    args = parser.parse_args()

    _, songs = load_corpus()
    chosen = [
        s
        for s in songs
        if in_set(s, args.set)
        and (HERE / "reference" / f"{s['id']}.txt").exists()
        and (not args.only or s["id"] in args.only)
    ]
    analyse(load_audio(excerpt_path(args.cache, chosen[0]["id"])))  # warm numba / caches
    rows = []
    contested = contested_songs()
    librosa = None
    if args.librosa_python:
        librosa = subprocess.Popen(
            [args.librosa_python, "-c", _LIBROSA_TIMER],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            text=True,
        )
    with tempfile.TemporaryDirectory() as tmp:
        for song in chosen:
            sid = song["id"]
            audio = load_audio(excerpt_path(args.cache, sid))
            best = float("inf")
            for _ in range(args.repeats):
                start = time.perf_counter()
                features = analyse(audio)
                best = min(best, time.perf_counter() - start)
            again = analyse(audio).beats
            ref = np.loadtxt(HERE / "reference" / f"{sid}.txt", ndmin=1)
            row = {"id": sid, "set": song["set"], "ref_bpm": tempo_of(trim(ref))}
            row["bpm"] = features.tempo_bpm
            row.update(score(ref, features.beats))
            row["deterministic"] = bool(np.array_equal(again, features.beats))
            row["first_beat"] = float(features.beats[0]) if len(features.beats) else float("nan")
            row["ref_first_beat"] = float(ref[0])
            row["ours_s"] = best
            row["contested"] = sid in contested
            if librosa is not None and librosa.stdin and librosa.stdout:
                # the same decoded samples, timed right after ours (one untimed warm-up call)
                npy = Path(tmp) / f"{sid}.npy"
                np.save(npy, audio.samples)
                librosa.stdin.write(f"{npy} {audio.sample_rate} {args.repeats}\n")
                librosa.stdin.flush()
                row["librosa_s"] = float(librosa.stdout.readline())
            rows.append(row)
    if librosa is not None:
        librosa.communicate()
    print_table(rows)
    if args.json:
        args.json.write_text(json.dumps(rows, indent=1))


def print_table(rows: list[dict]) -> None:
    cols = ["ref BPM", "ours BPM", "ratio", "F", "F oct", "CMLt", "AMLt", "1st beat", "ours s"]
    has_lib = any("librosa_s" in r for r in rows)
    if has_lib:
        cols.append("librosa s")
    print("| song | " + " | ".join(cols) + " |")
    print("|---" * (len(cols) + 1) + "|")
    for r in rows:
        cells = [
            f"{r['ref_bpm']:.1f}",
            f"{r['bpm']:.1f}",
            f"{r['ratio']:.2f}",
            f"{r['F']:.3f}",
            f"{r['Foct']:.3f}",
            f"{r['CMLt']:.3f}",
            f"{r['AMLt']:.3f}",
            f"{r['first_beat']:.2f} / {r['ref_first_beat']:.2f}",
            f"{r['ours_s']:.3f}",
        ]
        if has_lib:
            cells.append(f"{r.get('librosa_s', float('nan')):.3f}")
        print(f"| {r['id']}{' †' if r['contested'] else ''} | " + " | ".join(cells) + " |")
    mean = {k: float(np.mean([r[k] for r in rows])) for k in ("F", "Foct", "CMLt", "AMLt")}
    off = sum(1 for r in rows if abs(r["ratio"] - 1) > 0.04)
    line = (
        f"mean over {len(rows)}: F {mean['F']:.3f}, F oct {mean['Foct']:.3f}, "
        f"CMLt {mean['CMLt']:.3f}, AMLt {mean['AMLt']:.3f}; min F "
        f"{min(r['F'] for r in rows):.3f}; tempo off the reference level on {off}; "
        f"ours {sum(r['ours_s'] for r in rows):.2f} s total"
    )
    if has_lib:
        line += f", librosa {sum(r.get('librosa_s', 0) for r in rows):.2f} s total"
    if not all(r["deterministic"] for r in rows):
        line += "; NOT DETERMINISTIC"
    print(line)
    clear = [r for r in rows if not r["contested"]]
    if clear and len(clear) < len(rows):
        print(
            f"phase contested among the references on {len(rows) - len(clear)} (†); over the "
            f"other {len(clear)}: F {np.mean([r['F'] for r in clear]):.3f}, F oct "
            f"{np.mean([r['Foct'] for r in clear]):.3f}, min F {min(r['F'] for r in clear):.3f}, "
            f"{sum(r['F'] < 0.6 for r in clear)} below 0.6"
        )


if __name__ == "__main__":
    main()
