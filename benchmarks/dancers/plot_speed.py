"""Plot one dancer's body speed against the beats (docs/dancing.md).

    .venv/bin/python benchmarks/dancers/plot_speed.py TRAJ.npz [BEFORE.npz] --song ID
        [--start 20] [--seconds 6] -o OUT.png

TRAJ.npz comes from `sinews dance GENOME --song FILE --trajectory TRAJ.npz`. Draws the
mean node speed (smoothed as the beat-align score smooths it), its minima (kinematic
beats), our tracker's beats (saved in the trajectory) and the corpus's reference beats
(benchmarks/beats/reference/ID.txt). With BEFORE.npz, a second panel shows it too.
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent


def main() -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import scipy.ndimage

    from sinews.music import beat_lift
    from sinews.music.beat_align import SMOOTH_S, kinematic_beats, mean_speed
    from sinews.trajectory import Trajectory

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("trajectories", type=Path, nargs="+")
    parser.add_argument("--song", required=True)
    parser.add_argument("--start", type=float, default=4.0)
    parser.add_argument("--seconds", type=float, default=6.0)
    parser.add_argument("-o", "--output", type=Path, required=True)
    args = parser.parse_args()

    reference = np.loadtxt(HERE.parent / "beats" / "reference" / f"{args.song}.txt", ndmin=1)
    titles = ["after", "before"] if len(args.trajectories) == 2 else ["dancer"]
    fig, axes = plt.subplots(len(args.trajectories), 1, figsize=(9, 2.6 * len(titles)))
    axes = np.atleast_1d(axes)
    for ax, path, title in zip(axes, args.trajectories, titles, strict=True):
        traj = Trajectory.load(path)
        t = np.arange(traj.n_frames) / traj.fps
        speed = scipy.ndimage.gaussian_filter1d(
            mean_speed(traj.positions, traj.fps), SMOOTH_S * traj.fps
        )
        window = (t >= args.start) & (t <= args.start + args.seconds)
        ax.plot(t[window], speed[window], color="black", lw=1.2, label="mean node speed")
        pauses = kinematic_beats(traj.positions, traj.fps)
        pauses = pauses[window[pauses]]
        ax.plot(t[pauses], speed[pauses], "o", color="tab:red", ms=4, label="pauses")
        end = t[window][-1]
        for k, beat in enumerate(reference[(reference >= args.start) & (reference <= end)]):
            ax.axvline(beat, color="tab:blue", lw=1.0, label="reference beats" if k == 0 else None)
        if traj.beats is not None:
            ours = traj.beats[(traj.beats >= args.start) & (traj.beats <= t[window][-1])]
            ax.plot(ours, np.zeros_like(ours), "^", color="tab:green", ms=6, label="our beats")
        lift = beat_lift(traj.positions, traj.fps, reference)
        ax.set_title(f"{title}: beat lift {lift:.2f} against the reference beats", fontsize=10)
        ax.set_ylabel("m/s")
        ax.set_ylim(bottom=0)
    axes[-1].set_xlabel(f"seconds ({args.song})")
    axes[0].legend(loc="upper right", fontsize=7, ncol=4)
    fig.tight_layout()
    fig.savefig(args.output, dpi=100)
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
