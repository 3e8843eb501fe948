"""Does an entrained spring net's period follow the song? Its dominant period vs the beat's.

    .venv/bin/python benchmarks/figure_dance/net_periods.py DB [--run 1] [--individual ID]
        [--seconds 10] [--songs ID ...] [--json OUT]

Takes a spring-net dance run's best net (or ``--individual``) and lets it drive the lamp
to the first ``--seconds`` of each corpus song (benchmarks/beats/; $SINEWS_BEATS_CACHE),
hearing OUR analysis of the song. For each song: the dominant period of the net's output
masses (`dominant_period`, after 1 s) against the REFERENCE beat period (the median
interval of the reference beats in the window); the nearest simple ratio (1/4 … 4) and
how far off it the period is; the same net with its drive weights at zero (does the
period come from the music?); and the beat lift of the joints against the reference beats.

With --hand-drive, the net is not a run's but set by hand to show the mechanism: no
springs, every mass at 0 and of mass 1.09 (gene 0.1), each output mass pushed by
``beat_cos`` (+30, −30, +30, …): a net whose motion is the drive's alone.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
BEATS = HERE.parent / "beats"
sys.path.insert(0, str(BEATS))

from fetch import default_cache, excerpt_path  # noqa: E402

from sinews.experiments.kinds import chosen_of  # noqa: E402
from sinews.experiments.springnet.dance import DRIVE, dominant_period  # noqa: E402
from sinews.experiments.springnet.run import _settings  # noqa: E402
from sinews.experiments.springnet.settings import SpringNetSettings  # noqa: E402
from sinews.experiments.springnet.simulate import simulate  # noqa: E402
from sinews.figures.terms import joint_lift  # noqa: E402
from sinews.music import analyse_file  # noqa: E402
from sinews.store import RunStore  # noqa: E402

RATIOS = (0.25, 1 / 3, 0.5, 1.0, 2.0, 3.0, 4.0)
SONGS = ["supertux-christmas-theme", "supertux-battle-theme", "supertux-tropicalbreeze",
         "supertux-forest-sprint", "freedroidrpg-imperialarmy", "supertux-voc-daytime"]  # fmt: skip


def net_on(settings: SpringNetSettings, genes: np.ndarray, song: Path) -> dict[str, float]:
    """The net (and its undriven copy) to ``song``: periods against the reference beat."""
    music = analyse_file(song)
    heard = dataclasses.replace(settings, song_path=str(song), song_hash=music.song_hash)
    size = heard.encoding.size
    undriven = genes.copy()
    undriven[size:] = 0.5  # drive weight 0
    result, net = simulate(heard, np.stack([genes, undriven]), record_hz=100.0)
    assert net is not None and result.qpos is not None
    outputs = np.arange(result.figure.n_actuators) % heard.masses
    reference = np.loadtxt(BEATS / "reference" / f"{song.stem}.txt")
    beat = float(np.median(np.diff(reference[reference <= heard.seconds])))
    period = dominant_period(net[:, 0, outputs], 100.0)
    ratio = period / beat
    nearest = min(RATIOS, key=lambda r: abs(ratio / r - 1))
    model = result.figure.model()
    joints = [int(model.joint(j).qposadr[0]) for j in result.figure.joints]
    return {
        "beat_s": beat,
        "period_s": period,
        "ratio": ratio,
        "simple": nearest,
        "off_pct": 100 * abs(ratio / nearest - 1),
        "undriven_period_s": dominant_period(net[:, 1, outputs], 100.0),
        "lift_joints": joint_lift(result.qpos[:, 0, joints][:, :, None], 100.0, reference),
    }


def hand_driven(settings: SpringNetSettings) -> np.ndarray:
    """(G,) genes of a net moved by the drive alone (see --hand-drive)."""
    size, n = settings.encoding.size, settings.masses
    genes = np.full(settings.genome_size, 0.5)
    genes[:n] = 0.1
    genes[n : size - n] = 0.0
    drive = genes[size:].reshape(n, len(DRIVE))
    drive[:, DRIVE.index("beat_cos")] = np.resize([1.0, 0.0], n)
    return genes


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("db", type=Path)
    parser.add_argument("--run", type=int, default=1)
    parser.add_argument("--individual", type=int, default=None)
    parser.add_argument("--songs", nargs="+", default=SONGS)
    parser.add_argument("--json", type=Path, default=None)
    parser.add_argument("--hand-drive", action="store_true")
    args = parser.parse_args()
    with RunStore(args.db) as store:
        settings = _settings(store.run(args.run))
        chosen = chosen_of(store, args.run, args.individual)
    genes = np.asarray(chosen.genome, dtype=np.float64)
    print(f"individual {chosen.id} (generation {chosen.generation}), fitness {chosen.fitness}")
    if args.hand_drive:
        genes = hand_driven(settings)
        print("a net set by hand instead: no springs, beat_cos on every mass")
    rows = {}
    for song in args.songs:
        rows[song] = net_on(settings, genes, excerpt_path(default_cache(), song))
        print(f"{song:26s} " + " ".join(f"{k} {v:.3f}" for k, v in rows[song].items()))
    if args.json:
        args.json.write_text(json.dumps({"individual": chosen.id, "songs": rows}, indent=1))


if __name__ == "__main__":
    main()
