"""Reference beats for the corpus, from independent trackers (dev only; eval venv).

    /work/evalvenv/bin/python benchmarks/beats/make_reference.py [--cache DIR] [--only ID ...]

Runs madmom 0.16.1 (RNNBeatProcessor + DBNBeatTrackingProcessor, 100 fps), essentia
(RhythmExtractor2013, method "multifeature") and librosa 0.11 (`beat.beat_track`, defaults)
on each excerpt and writes reference/raw/ID.TRACKER.txt (one beat time a line, seconds).
Then the consensus rule (also in docs/beats.md):

- score each pair of trackers with F (70 ms, beats after 5 s);
- the song is kept if the best-agreeing pair has F >= 0.8; its reference is that pair's
  madmom beats if madmom is in the pair, else essentia's;
- otherwise the song is dropped (status "disagree").

reference/ID.txt holds the chosen reference beats and reference/summary.tsv the pairwise
agreements. The trackers' own metrical level is kept: where the agreeing pair is at half
or double the level a listener would tap, the song still counts, and the harness also
reports octave-tolerant F.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

# madmom 0.16.1 still uses the aliases numpy 1.24 removed.
for _alias, _type in (("int", int), ("float", float), ("bool", bool), ("complex", complex)):
    setattr(np, _alias, _type)

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from fetch import (  # noqa: E402
    PAIR_COLUMNS,
    REFERENCE_TRACKERS,
    default_cache,
    excerpt_path,
    load_corpus,
)
from metrics import f_measure, tempo_of, trim  # noqa: E402


def run_madmom(path: Path) -> np.ndarray:
    from madmom.features.beats import DBNBeatTrackingProcessor, RNNBeatProcessor

    act = RNNBeatProcessor()(str(path))
    return np.asarray(DBNBeatTrackingProcessor(fps=100)(act), dtype=float)


def run_essentia(path: Path) -> np.ndarray:
    import essentia.standard as es

    audio = es.MonoLoader(filename=str(path), sampleRate=44100)()
    _, beats, *_ = es.RhythmExtractor2013(method="multifeature")(audio)
    return np.asarray(beats, dtype=float)


def run_librosa(path: Path) -> np.ndarray:
    import librosa

    y, sr = librosa.load(str(path), sr=None, mono=True)
    _, beats = librosa.beat.beat_track(y=y, sr=sr, units="time")
    return np.asarray(beats, dtype=float)


RUNNERS = {"madmom": run_madmom, "essentia": run_essentia, "librosa": run_librosa}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cache", type=Path, default=default_cache())
    parser.add_argument("--only", nargs="*", default=None)
    parser.add_argument("--rerun", action="store_true", help="run trackers even if raw files exist")
    args = parser.parse_args()
    _, songs = load_corpus()
    raw_dir = HERE / "reference" / "raw"
    raw_dir.mkdir(parents=True, exist_ok=True)
    head = ["id", "set", *(f"{t}_bpm" for t in REFERENCE_TRACKERS)]
    head += [*PAIR_COLUMNS, "status", "reference"]
    rows = ["\t".join(head)]
    for song in songs:
        sid = song["id"]
        if args.only and sid not in args.only:
            continue
        beats = {}
        for name in REFERENCE_TRACKERS:
            out = raw_dir / f"{sid}.{name}.txt"
            if args.rerun or not out.exists():
                start = time.perf_counter()
                b = RUNNERS[name](excerpt_path(args.cache, sid))
                np.savetxt(out, b, fmt="%.3f")
                print(f"{sid} {name}: {time.perf_counter() - start:.1f} s", file=sys.stderr)
            beats[name] = np.atleast_1d(np.loadtxt(out, ndmin=1))
        pair_f = {
            (a, b): f_measure(trim(beats[a]), trim(beats[b])) for a, b in PAIR_COLUMNS.values()
        }
        (a, b), best = max(pair_f.items(), key=lambda kv: kv[1])
        ref_file = HERE / "reference" / f"{sid}.txt"
        if best >= 0.8:
            chosen = "madmom" if "madmom" in (a, b) else "essentia"
            np.savetxt(ref_file, beats[chosen], fmt="%.3f")
            status = "kept"
        else:
            chosen = "-"
            ref_file.unlink(missing_ok=True)
            status = "disagree"
        rows.append(
            "\t".join(
                [sid, song["set"]]
                + [f"{tempo_of(trim(beats[t])):.1f}" for t in REFERENCE_TRACKERS]
                + [f"{pair_f[p]:.3f}" for p in PAIR_COLUMNS.values()]
                + [status, chosen]
            )
        )
    if not args.only:
        (HERE / "reference" / "summary.tsv").write_text("\n".join(rows) + "\n")
    print("\n".join(rows))


if __name__ == "__main__":
    main()
