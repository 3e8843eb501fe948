"""How well dancers follow real music: beat lift against REFERENCE beats, smoothness, stretch.

    .venv/bin/python benchmarks/dancers/evaluate.py [--set SET|all (fetch.SEEN)] [--dancers 16]
        [--seconds 50] [--genome-seed 1] [--evolve N] [--only ID ...] [--json OUT]

Uses the beat corpus of benchmarks/beats/ (audio: `python3 benchmarks/beats/fetch.py`;
$SINEWS_BEATS_CACHE). For each song with reference beats, the same random dancers
(`random_genomes(genome-seed, dancers)`, wiggle seeds 0 … dancers-1) dance the excerpt,
listening to OUR analysis of it (as in the product), and are scored against the
corpus's REFERENCE beats:

- lift: beat-align with the reference beats minus its mean over 16 evenly spaced phase
  shifts (`sinews.music.beat_lift`); also with every responder off (wiggle and home only);
- align: the raw beat-align score (AIST++) with the reference beats;
- smooth: `sinews.music.smoothness` (share of motion energy below 4 Hz);
- stretch: per frame, the largest length / rest length over the springs; "ok" is the
  share of frames where it is at most 1.5, pooled over dancers; p50 / p95 of the ratio;
- move: how far the body moves, the rms distance of each node from its mean position,
  in cm, averaged over all nodes, over the trunk (neck, chest, belly, pelvis, hips) and
  over the knees.

With --evolve N, the first N chosen songs also get an evolution with the product's
defaults (population 16 x 10 generations, GA, fitness from our own beats, serial, run
seed 0) in a temporary store; its best is replayed and its lift against the REFERENCE
beats reported.
"""

from __future__ import annotations

import argparse
import json
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
BEATS = HERE.parent / "beats"
sys.path.insert(0, str(BEATS))

from fetch import SETS, default_cache, excerpt_path, in_set, load_corpus  # noqa: E402

STRETCH_LIMIT = 1.5
TRUNK = ("neck", "chest", "belly", "pelvis", "l_hip", "r_hip")
KNEES = ("l_knee", "r_knee")


def excursion(traj) -> tuple[float, float, float]:
    """rms distance (cm) of the nodes from their mean positions: all nodes, trunk, knees."""
    p = traj.positions.astype(np.float64)
    rms = 100.0 * np.sqrt((np.linalg.norm(p - p.mean(axis=0), axis=2) ** 2).mean(axis=0))
    names = list(traj.node_names)
    trunk = float(np.mean([rms[names.index(n)] for n in TRUNK]))
    knees = float(np.mean([rms[names.index(n)] for n in KNEES]))
    return float(rms.mean()), trunk, knees


def stretch_ratios(traj, rest_length: np.ndarray) -> np.ndarray:
    """(T,) per frame, the largest spring length / rest length."""
    p = traj.positions.astype(np.float64)
    i, j = traj.edges[:, 0], traj.edges[:, 1]
    length = np.linalg.norm(p[:, j] - p[:, i], axis=2)
    return (length / rest_length[None, :]).max(axis=1)


def score_dancers(trajs, bodies, beats) -> dict[str, list[float]]:
    from sinews.music import beat_align_score, beat_lift, smoothness

    out: dict[str, list[float]] = {
        "lift": [], "align": [], "smooth": [], "ok": [], "move": [], "trunk": [], "knees": []
    }  # fmt: skip
    ratios = []
    for traj, body in zip(trajs, bodies, strict=True):
        out["lift"].append(beat_lift(traj.positions, traj.fps, beats))
        out["align"].append(beat_align_score(traj.positions, traj.fps, beats))
        out["smooth"].append(smoothness(traj.positions, traj.fps))
        r = stretch_ratios(traj, body.rest_length)
        out["ok"].append(float(np.mean(r <= STRETCH_LIMIT)))
        for key, value in zip(("move", "trunk", "knees"), excursion(traj), strict=True):
            out[key].append(value)
        ratios.append(r)
    pooled = np.concatenate(ratios)
    out["ratio_p50"] = [float(np.percentile(pooled, 50))]
    out["ratio_p95"] = [float(np.percentile(pooled, 95))]
    out["failed"] = [float(sum(t.failed for t in trajs))]
    return out


def evolve_best_lift(path: Path, seconds: float, beats: np.ndarray) -> dict[str, float]:
    """Evolve 16 x 10 on ``path`` (product defaults), replay the best, score vs ``beats``."""
    from sinews.evolve import SerialEvaluator
    from sinews.experiments.dancers.run import KIND
    from sinews.experiments.kinds import best_of
    from sinews.music import beat_lift, smoothness
    from sinews.store import RunStore

    with tempfile.TemporaryDirectory() as tmp, RunStore(Path(tmp) / "runs.db") as store:
        run_id = KIND.create_run(
            store,
            subject="dancers",
            file_values={},
            options={"song": str(path), "seconds": seconds, "population": 16,
                     "generations": 10, "seed": 0},
        )  # fmt: skip
        KIND.run(store, run_id, evaluator=SerialEvaluator())
        best = best_of(store, run_id)
        (replay,) = KIND.replay(store, [best])
        traj = replay.trajectory
        return {
            "lift": beat_lift(traj.positions, traj.fps, beats),
            "lift_ours": beat_lift(traj.positions, traj.fps, traj.beats),
            "smooth": smoothness(traj.positions, traj.fps),
        }


def main() -> None:
    from sinews.dancers import develop
    from sinews.experiments.dancers.simulate import dance, random_genomes
    from sinews.music import analyse_file

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cache", type=Path, default=default_cache())
    parser.add_argument("--set", default="tune", choices=(*SETS, "all"))
    parser.add_argument("--dancers", type=int, default=16)
    parser.add_argument("--seconds", type=float, default=50.0)
    parser.add_argument("--genome-seed", type=int, default=1)
    parser.add_argument("--evolve", type=int, default=0)
    parser.add_argument("--only", nargs="*", default=None)
    parser.add_argument("--json", type=Path, default=None)
    args = parser.parse_args()

    _, songs = load_corpus()
    chosen = [
        s
        for s in songs
        if in_set(s, args.set)
        and (BEATS / "reference" / f"{s['id']}.txt").exists()
        and (not args.only or s["id"] in args.only)
    ]
    genomes = random_genomes(args.genome_seed, args.dancers)
    seeds = list(range(args.dancers))
    rows = []
    print(
        "| song | ref BPM | ours BPM | lift | lift, responders off | align | smooth "
        "| frames ≤ 1.5× | stretch p50 / p95 | move cm (trunk, knees) | evolved lift (ours) |"
    )
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    start = time.perf_counter()
    for n, song in enumerate(chosen):
        path = excerpt_path(args.cache, song["id"])
        beats = np.loadtxt(BEATS / "reference" / f"{song['id']}.txt", ndmin=1)
        music = analyse_file(path)
        seconds = min(args.seconds, music.duration)
        bodies = [develop(g, n_bands=music.n_bands) for g in genomes]
        on = score_dancers(dance(genomes, seconds, music=music, seeds=seeds), bodies, beats)
        off = score_dancers(
            dance(genomes, seconds, music=music, seeds=seeds, responders=False), bodies, beats
        )
        row = {
            "id": song["id"],
            "ref_bpm": 60.0 / float(np.median(np.diff(beats))),
            "ours_bpm": music.tempo_bpm,
            **{k: float(np.mean(v)) for k, v in on.items()},
            "lift_off": float(np.mean(off["lift"])),
            "lifts": on["lift"],
            "oks": on["ok"],
        }
        evolved = ""
        if n < args.evolve:
            row["evolved"] = evolve_best_lift(path, seconds, beats)
            evolved = f"{row['evolved']['lift']:.3f} ({row['evolved']['lift_ours']:.3f})"
        rows.append(row)
        print(
            f"| {row['id']} | {row['ref_bpm']:.1f} | {row['ours_bpm']:.1f} | "
            f"{row['lift']:.3f} | {row['lift_off']:.3f} | {row['align']:.3f} | "
            f"{row['smooth']:.2f} | {row['ok']:.3f} | "
            f"{row['ratio_p50']:.2f} / {row['ratio_p95']:.2f} | "
            f"{row['move']:.1f} ({row['trunk']:.1f}, {row['knees']:.1f}) | {evolved} |",
            flush=True,
        )
    lifts = np.array([r["lift"] for r in rows])
    oks = np.concatenate([r["oks"] for r in rows])
    summary = {
        "songs": len(rows),
        "mean_lift": float(lifts.mean()),
        "min_lift": float(lifts.min()),
        "songs_lift_le_0": int((lifts <= 0).sum()),
        "mean_lift_off": float(np.mean([r["lift_off"] for r in rows])),
        "mean_align": float(np.mean([r["align"] for r in rows])),
        "mean_smooth": float(np.mean([r["smooth"] for r in rows])),
        "move_trunk_knees_cm": [
            float(np.mean([r[k] for r in rows])) for k in ("move", "trunk", "knees")
        ],
        "frames_ok": float(np.mean(oks)),
        "dancer_ok_min_p5_p50": [
            float(np.min(oks)),
            float(np.percentile(oks, 5)),
            float(np.median(oks)),
        ],
        "failed": int(sum(r["failed"] for r in rows)),
        "seconds": time.perf_counter() - start,
    }
    if args.evolve:
        evolved = [r["evolved"]["lift"] for r in rows if "evolved" in r]
        summary["evolved_mean_lift"] = float(np.mean(evolved))
        summary["evolved_min_lift"] = float(np.min(evolved))
    print(
        f"\n{summary['songs']} songs: mean lift {summary['mean_lift']:.3f} "
        f"(min {summary['min_lift']:.3f}, {summary['songs_lift_le_0']} songs ≤ 0; "
        f"responders off {summary['mean_lift_off']:.3f}), align {summary['mean_align']:.3f}, "
        f"smooth {summary['mean_smooth']:.2f}; move "
        + " / ".join(f"{v:.1f}" for v in summary["move_trunk_knees_cm"])
        + " cm (all / trunk / knees); frames with every spring ≤ 1.5×: "
        f"{summary['frames_ok']:.3f} (per dancer min / p5 / median "
        + " / ".join(f"{v:.3f}" for v in summary["dancer_ok_min_p5_p50"])
        + f"); failed {summary['failed']}"
        + (
            f"; evolved mean lift {summary['evolved_mean_lift']:.3f} "
            f"(min {summary['evolved_min_lift']:.3f})"
            if args.evolve
            else ""
        )
        + f"; {summary['seconds']:.0f} s"
    )
    if args.json:
        args.json.write_text(json.dumps({"rows": rows, "summary": summary}, indent=1))


if __name__ == "__main__":
    main()
