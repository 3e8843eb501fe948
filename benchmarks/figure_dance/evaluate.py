"""Does an evolved dancing figure follow real music? Beat lift against REFERENCE beats.

    .venv/bin/python benchmarks/figure_dance/evaluate.py DB [--run 1] [--individual ID]
        [--seconds 10] [--songs ID ...] [--json OUT]

Takes a GP dance run's best program (or ``--individual``) and lets it dance the first
``--seconds`` of each corpus song (benchmarks/beats/, audio from `fetch.py`;
$SINEWS_BEATS_CACHE), hearing OUR analysis of the song as in the product. Scored
against the corpus's REFERENCE beats (`benchmarks/beats/reference/`):

- lift_joints: the beat lift of the driven joints' angles at the control rate, the
  run's own measure (`sinews.figures.terms.joint_lift`);
- lift_bodies: the beat lift of the figure's bodies' (x, z) positions at 60 fps, the
  end-effector view (`sinews.music.beat_lift`);
- lift_own: lift_joints against our tracker's beats (what the run was rated by);
- fallen, smooth: the run's own style terms on that song.

With --beats-of ID, every dance is scored against that song's reference beats instead
(a control: a dance to one song against another's beats should lift about 0).
With --videos DIR, each dance is also drawn as DIR/SONG.mp4 with the song as sound, and
its joint and body speeds over 4-8 s with the reference beats as DIR/SONG.png.
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

from sinews.experiments.gp.run import _settings  # noqa: E402
from sinews.experiments.gp.settings import GPSettings, Runtime  # noqa: E402
from sinews.experiments.gp.simulate import measure_programs  # noqa: E402
from sinews.experiments.kinds import chosen_of  # noqa: E402
from sinews.figures.terms import joint_lift  # noqa: E402
from sinews.music import analyse_file, beat_lift  # noqa: E402
from sinews.music.beat_align import mean_speed  # noqa: E402
from sinews.render import render_figure  # noqa: E402
from sinews.store import RunStore  # noqa: E402


def dance_on(
    settings: GPSettings,
    program: str,
    song: Path,
    seconds: float,
    video: Path | None = None,
    beats_of: str | None = None,
) -> dict[str, float]:
    """The program's dance to ``song`` (first ``seconds``), scored against reference beats
    (and drawn to ``video``, an MP4 with the song, if given)."""
    music = analyse_file(song)
    heard = dataclasses.replace(settings, song_path=str(song), song_hash=music.song_hash,
                                seconds=seconds)  # fmt: skip
    done = measure_programs(heard, heard.parse([program]), Runtime(record_hz=60.0), record=True)
    reference = np.loadtxt(BEATS / "reference" / f"{beats_of or song.stem}.txt")
    result = done.result
    assert result.qpos is not None and result.body_pos is not None
    figure = heard.task.figure
    model = figure.model()
    driven = [int(model.joint(j).qposadr[0]) for j in heard.task.joints]
    terms = dict(zip(heard.task.weights, done.terms[0].tolist(), strict=True))
    angles = result.qpos[:, 0, driven][:, :, None]
    bodies = result.body_pos[:, 0][:, :, [0, 2]]
    if video is not None:
        render_figure(figure, result.trajectory(0), video, size=(480, 360), audio=song,
                      title=f"{song.stem}, lift {terms['lift']:.2f}")  # fmt: skip
        speed_plot(angles, bodies, reference, video.with_suffix(".png"), song.stem)
    return {
        "bpm": float(music.tempo_bpm),
        "lift_joints": joint_lift(angles, 60.0, reference),
        "lift_bodies": beat_lift(bodies, 60.0, reference),
        "lift_own": terms["lift"],
        "fallen": terms["fallen"],
        "smooth": terms["smooth"],
        "failed": bool(done.failed[0]),
    }


def speed_plot(
    angles: np.ndarray, bodies: np.ndarray, beats: np.ndarray, path: Path, title: str
) -> None:
    """Mean joint speed and mean body speed over 4 s from t = 4 s, with the reference beats."""
    from matplotlib.figure import Figure

    fps = 60.0
    window = slice(round(4 * fps), round(8 * fps))
    t = np.arange(len(angles))[window] / fps
    figure = Figure(figsize=(8, 3), dpi=100)
    axes = figure.add_subplot()
    for name, points, unit in (("joints", angles, "rad/s"), ("bodies", bodies, "m/s x 10")):
        speed = mean_speed(points, fps)[window] * (10.0 if name == "bodies" else 1.0)
        axes.plot(t, speed, label=f"mean {name} speed, {unit}")
    for beat in beats[(beats >= t[0]) & (beats <= t[-1])]:
        axes.axvline(beat, color="0.6", linewidth=0.8)
    axes.set_xlabel("s (grey: reference beats)")
    axes.set_title(title)
    axes.legend(loc="upper right", fontsize=8)
    figure.tight_layout()
    figure.savefig(path)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("db", type=Path)
    parser.add_argument("--run", type=int, default=1)
    parser.add_argument("--individual", type=int, default=None)
    parser.add_argument("--seconds", type=float, default=10.0)
    parser.add_argument("--songs", nargs="+", default=["supertux-forest-sprint",
                        "supertux-battle-theme", "hedgewars-oriental"])  # fmt: skip
    parser.add_argument("--json", type=Path, default=None)
    parser.add_argument("--videos", type=Path, default=None, help="folder for one MP4 a song")
    parser.add_argument("--beats-of", default=None, help="score against this song's beats")
    args = parser.parse_args()
    with RunStore(args.db) as store:
        settings = _settings(store.run(args.run))
        chosen = chosen_of(store, args.run, args.individual)
    print(f"individual {chosen.id} (generation {chosen.generation}): {chosen.genome}")
    rows = {}
    for song in args.songs:
        video = None if args.videos is None else args.videos / f"{song}.mp4"
        row = dance_on(settings, str(chosen.genome), excerpt_path(default_cache(), song),
                       args.seconds, video, args.beats_of)  # fmt: skip
        rows[song] = row
        print(f"{song:26s} " + " ".join(f"{k} {v:.3f}" for k, v in row.items()))
    if args.json:
        args.json.write_text(json.dumps({"individual": chosen.id, "songs": rows}, indent=1))


if __name__ == "__main__":
    main()
