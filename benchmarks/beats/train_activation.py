"""Train the beat activation network (`sinews.music.beatnet`) on the corpus's reference beats.

    .venv/bin/python benchmarks/beats/train_activation.py features     # inputs of every song
    .venv/bin/python benchmarks/beats/train_activation.py cv [--folds 0 1] [--json ROWS]
    .venv/bin/python benchmarks/beats/train_activation.py summary ROWS...  # CV rows together
    .venv/bin/python benchmarks/beats/train_activation.py train -o src/sinews/music/beatnet.npz
    .venv/bin/python benchmarks/beats/train_activation.py score --set confirm12 [--net FILE]

Needs the excerpts (fetch.py) and PyTorch (dev only: `pip install torch==2.13.0`); the
shipped network runs in numpy. `features` stores, for each song of the seen sets, the
network's inputs at 60 fps and the beats of the envelope tracker (the baseline) in
CACHE/activation/ID.npz. `cv` trains one network per fold on the other folds' songs (training
seed --seed) and scores each song with the network that never saw it, beside the baseline;
`train` fits one network per seed on every seen set (`SEEN`) and writes them together (the
shipped activation is their mean); `score` stores one set's features and scores it with the
networks of a weights file (default: the shipped ones), beside the baseline, so only `score`
runs a tracker on the unseen set. Beats are tracked on `sinews.music.beatnet.beat_strength`,
as in `analyse`. All settings (`Settings`) were fixed before the first run (docs/beats.md, "A
network with seconds of context"); `--stretch` (session 39, off by default) time-stretches
the training crops.
"""

from __future__ import annotations

import argparse
import json
import sys
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from fetch import SEEN, SETS, default_cache, excerpt_path, load_corpus  # noqa: E402
from metrics import score  # noqa: E402

from sinews.music.beatnet import NET_FPS as FPS  # noqa: E402

FOLDS = (
    ("tune", "confirm3"),
    ("heldout", "confirm", "confirm2", "confirm5", "confirm6"),
    ("confirm4", "confirm7", "confirm8"),
    ("confirm9",),
    ("confirm10", "confirm11", "confirm12"),
)


@dataclass(frozen=True)
class Settings:
    channels: int = 24
    taps: int = 5
    dilations: tuple[int, ...] = (1, 2, 4, 8, 16, 32, 64, 128)
    dropout: float = 0.1
    learning_rate: float = 2e-3
    epochs: int = 60
    batch: int = 8
    crop_s: float = 30.0
    gain_db: float = 6.0
    stretch: float = 1.0
    """Crops are time-stretched by a factor drawn log-uniformly in [1/stretch, stretch]
    (1: none, the shipped networks' recipe)."""
    tempo_weight: float = 0.0
    """Weight of a tempo classifier trained beside the beats (session 42; 0: none, the shipped
    recipe). It reads the last hidden state averaged over the crop, has `TEMPO_BINS` 1-BPM
    classes, and is dropped on export: it shapes only the shared weights."""
    seed: int = 0


TEMPO_BINS = 300
"""The tempo classifier's classes: 0-299 BPM in 1-BPM bins (Böck, Davies & Krebs 2019)."""


def tempo_target(beats: np.ndarray, song_beats: np.ndarray) -> np.ndarray:
    """(TEMPO_BINS,) the soft tempo class of a crop whose reference beats (s) are ``beats``:
    1 at 60 / their median interval, 0.5 and 0.25 one and two bins away, summing to 1 (the
    song's tempo, from ``song_beats``, where the crop holds fewer than three beats)."""
    spans = np.diff(beats) if len(beats) >= 3 else np.diff(song_beats)
    centre = int(np.clip(round(60.0 / float(np.median(spans))), 2, TEMPO_BINS - 3))
    y = np.zeros(TEMPO_BINS, dtype=np.float32)
    y[centre - 2 : centre + 3] = (0.25, 0.5, 1.0, 0.5, 0.25)
    return y / y.sum()


def songs_of(sets: tuple[str, ...]) -> list[dict]:
    _, songs = load_corpus()
    return [
        s for s in songs if s["set"] in sets and (HERE / "reference" / f"{s['id']}.txt").exists()
    ]


def reference(song_id: str) -> np.ndarray:
    return np.loadtxt(HERE / "reference" / f"{song_id}.txt", ndmin=1)


def features(cache: Path, sets: tuple[str, ...]) -> None:
    """Store the network inputs (levels, onsets) and the envelope tracker's beats of each song
    of ``sets``."""
    from sinews.music import load_audio
    from sinews.music.analysis import band_levels
    from sinews.music.beats import onset_envelope, track
    from sinews.music.onsets import onset_strength
    from sinews.music.spectrum import DEFAULT_BANDS, band_centres, band_edges

    out = cache / "activation"
    out.mkdir(parents=True, exist_ok=True)
    edges = band_edges(DEFAULT_BANDS)
    for song in songs_of(sets):
        path = out / f"{song['id']}.npz"
        if path.exists():
            continue
        audio = load_audio(excerpt_path(cache, song["id"]))
        _, onset_levels = band_levels(audio, FPS, edges)
        onset = onset_strength(onset_levels, FPS)
        _, baseline = track(onset_envelope(onset, band_centres(edges)), FPS)
        np.savez(path, onset_levels=onset_levels, onset=onset, baseline=baseline)
        print(f"features {song['id']}", file=sys.stderr)


def load_song(cache: Path, song_id: str) -> dict[str, np.ndarray]:
    with np.load(cache / "activation" / f"{song_id}.npz") as data:
        return {k: data[k] for k in data.files}


def targets(n_frames: int, beats: np.ndarray) -> np.ndarray:
    """(T,) 1 at the frame nearest each beat, 0.5 at its neighbours, else 0."""
    y = np.zeros(n_frames, dtype=np.float32)
    frames = np.round(beats * FPS).astype(np.int64)
    frames = frames[(frames >= 0) & (frames < n_frames)]
    for side in (-1, 1):
        near = np.clip(frames + side, 0, n_frames - 1)
        y[near] = np.maximum(y[near], 0.5)
    y[frames] = 1.0
    return y


def fit(cache: Path, train_ids: list[str], settings: Settings):  # type: ignore[no-untyped-def]
    """Train a network on ``train_ids``; returns its `sinews.music.beatnet.BeatNet`."""
    import torch

    from sinews.music.beatnet import _resample, net_input

    torch.set_num_threads(1)  # two trainings side by side beat one on two threads here
    torch.manual_seed(settings.seed)
    rng = np.random.default_rng(settings.seed)
    data = []
    for sid in train_ids:
        song, beats = load_song(cache, sid), reference(sid)
        onset = song["onset"]
        data.append((song["onset_levels"], onset, targets(len(onset), beats), beats))
    n_in = 2 * data[0][0].shape[1]
    model = _model(n_in, settings)
    opt = torch.optim.Adam(model.parameters(), lr=settings.learning_rate)
    crop = int(settings.crop_s * FPS)
    steps = max(1, len(data) // settings.batch)
    for epoch in range(settings.epochs):
        order = rng.permutation(len(data))
        total = total_tempo = 0.0
        model.train()
        for step in range(steps):
            xs, ys, crop_beats = [], [], []
            for i in order[step * settings.batch : (step + 1) * settings.batch]:
                levels, onset, y, beats = data[i]
                if settings.stretch == 1.0:
                    start, factor = int(rng.integers(0, max(1, len(y) - crop))), 1.0
                    lv, on, yy = (a[start : start + crop] for a in (levels, onset, y))
                else:  # crop frame k is the song's frame start + k * factor
                    factor = np.exp(rng.uniform(-1.0, 1.0) * np.log(settings.stretch))
                    span = min(len(y) - 1.0, crop * factor)
                    start = int(rng.integers(0, max(1, int(len(y) - span))))
                    at = start + np.arange(int(span / factor)) * factor
                    lv, on = _resample(levels, at), _resample(onset, at)
                    yy = targets(len(at), (beats * FPS - start) / factor / FPS)
                gain = np.float32(rng.uniform(-settings.gain_db, settings.gain_db))
                xs.append(net_input(lv + gain, on))
                ys.append(yy)
                crop_beats.append(((beats * FPS - start) / factor / FPS, beats / factor))
            length = min(len(y) for y in ys)
            x = torch.from_numpy(np.stack([a[:length] for a in xs])).transpose(1, 2)
            target = torch.from_numpy(np.stack([a[:length] for a in ys]))
            logits, tempo_logits = model(x)
            loss = torch.nn.functional.binary_cross_entropy_with_logits(logits, target)
            if settings.tempo_weight > 0:
                tempi = np.stack([
                    tempo_target(b[(b >= 0) & (b < length / FPS)], whole)
                    for b, whole in crop_beats
                ])  # fmt: skip
                log_p = torch.log_softmax(tempo_logits, dim=1)
                tempo_loss = -(torch.from_numpy(tempi) * log_p).sum(dim=1).mean()
                loss = loss + settings.tempo_weight * tempo_loss
                total_tempo += float(tempo_loss.detach())
            opt.zero_grad()
            loss.backward()
            opt.step()
            total += float(loss.detach())
        print(f"epoch {epoch + 1}: loss {total / steps:.4f} (tempo {total_tempo / steps:.4f})",
              file=sys.stderr)  # fmt: skip
    return model.export()


def _model(n_in: int, settings: Settings):  # type: ignore[no-untyped-def]
    """The torch twin of `sinews.music.beatnet.BeatNet`, untrained (``export()`` gives that)."""
    import torch
    from torch import nn

    from sinews.music.beatnet import BeatNet

    class Model(nn.Module):
        def __init__(self) -> None:
            super().__init__()
            c = settings.channels
            self.inp = nn.Conv1d(n_in, c, 1)
            self.convs = nn.ModuleList(
                nn.Conv1d(c, c, settings.taps, dilation=d, padding=(settings.taps // 2) * d)
                for d in settings.dilations
            )
            self.mixes = nn.ModuleList(nn.Conv1d(c, c, 1) for _ in settings.dilations)
            self.drop = nn.Dropout(settings.dropout)
            self.out = nn.Conv1d(c, 1, 1)
            # made only when trained, so the shipped recipe draws the same random numbers
            self.tempo = nn.Linear(c, TEMPO_BINS) if settings.tempo_weight > 0 else None

        def forward(self, x: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor | None]:
            """(B, T) beat logits and (B, TEMPO_BINS) tempo logits (None without the head)
            of (B, F, T) features."""
            h = self.inp(x)
            for conv, mix in zip(self.convs, self.mixes, strict=True):
                h = h + mix(self.drop(nn.functional.elu(conv(h))))
            last = nn.functional.elu(h)
            tempo = None if self.tempo is None else self.tempo(self.drop(last.mean(dim=2)))
            return self.out(last)[:, 0, :], tempo

        def export(self) -> BeatNet:
            def arr(t: torch.Tensor) -> np.ndarray:
                return t.detach().numpy().astype(np.float32)

            return BeatNet(
                in_w=arr(self.inp.weight[:, :, 0].T),
                in_b=arr(self.inp.bias),
                conv_w=np.stack([arr(c.weight.permute(2, 1, 0)) for c in self.convs]),
                conv_b=np.stack([arr(c.bias) for c in self.convs]),
                mix_w=np.stack([arr(m.weight[:, :, 0].T) for m in self.mixes]),
                mix_b=np.stack([arr(m.bias) for m in self.mixes]),
                out_w=arr(self.out.weight[0, :, 0]),
                out_b=arr(self.out.bias[0]),
                dilations=np.array(settings.dilations, dtype=np.int64),
            )

    return Model()


def rate(cache: Path, nets, ids: list[str]) -> list[dict]:  # type: ignore[no-untyped-def]
    """Score each song's beats tracked on ``nets``' beat strength, beside the baseline's."""
    from sinews.music.beatnet import beat_strength
    from sinews.music.beats import track
    from sinews.music.spectrum import DEFAULT_BANDS, band_centres, band_edges

    centres = band_centres(band_edges(DEFAULT_BANDS))
    rows = []
    for sid in ids:
        song = load_song(cache, sid)
        strength = beat_strength(song["onset_levels"], song["onset"], centres, FPS, nets)
        _, beats = track(strength, FPS)
        ref = reference(sid)
        ours, base = score(ref, beats), score(ref, song["baseline"])
        rows.append({"id": sid, "F": ours["F"], "Foct": ours["Foct"], "F0": base["F"],
                     "Foct0": base["Foct"], "ratio": ours["ratio"]})  # fmt: skip
    return rows


def summary(rows: list[dict], sets: dict[str, str]) -> None:
    for r in rows:
        flag = "  <<" if r["F"] < r["F0"] - 0.2 else ("  >>" if r["F"] > r["F0"] + 0.2 else "")
        print(
            f"{r['id']:40s} F {r['F0']:.3f} -> {r['F']:.3f}  oct {r['Foct0']:.3f} -> "
            f"{r['Foct']:.3f}  ratio {r['ratio']:.2f}{flag}"
        )
    print("| set | songs | F tracker | F net | octave F tracker | octave F net | min F net |")
    print("|---|---|---|---|---|---|---|")
    for name in (*SETS, "all"):
        part = [r for r in rows if name == "all" or sets[r["id"]] == name]
        if not part:
            continue
        m = {k: np.mean([r[k] for r in part]) for k in ("F0", "F", "Foct0", "Foct")}
        print(
            f"| {name} | {len(part)} | {m['F0']:.3f} | {m['F']:.3f} | {m['Foct0']:.3f} | "
            f"{m['Foct']:.3f} | {min(r['F'] for r in part):.3f} |"
        )
    print(
        f"below 0.6: tracker {sum(r['F0'] < 0.6 for r in rows)}, net "
        f"{sum(r['F'] < 0.6 for r in rows)}"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("command", choices=("features", "cv", "summary", "train", "score"))
    parser.add_argument("rows", nargs="*", type=Path, help="summary: the cv --json files")
    parser.add_argument("--folds", nargs="*", type=int, default=list(range(len(FOLDS))))
    parser.add_argument("--json", type=Path, default=None)
    parser.add_argument("--cache", type=Path, default=default_cache())
    parser.add_argument("-o", "--output", type=Path, default=None)
    parser.add_argument("--set", default=SETS[-1], choices=SETS)
    parser.add_argument("--net", type=Path, default=None)
    parser.add_argument("--seed", type=int, default=Settings.seed, help="cv: the training seed")
    parser.add_argument("--stretch", type=float, default=Settings.stretch, help="see Settings")
    parser.add_argument(
        "--tempo-weight", type=float, default=Settings.tempo_weight, help="see Settings"
    )
    parser.add_argument(
        "--seeds", nargs="*", type=int, default=[0, 1, 2, 3], help="train: one net each"
    )
    args = parser.parse_args()
    from sinews.music.beatnet import load_nets, save_nets

    settings = Settings(seed=args.seed, stretch=args.stretch, tempo_weight=args.tempo_weight)
    sets = {s["id"]: s["set"] for s in songs_of(SETS)}
    if args.command == "features":
        features(args.cache, SEEN)
    elif args.command == "cv":
        rows = []
        for k in args.folds:
            train = [s["id"] for s in songs_of(SEEN) if s["set"] not in FOLDS[k]]
            net = fit(args.cache, train, settings)
            if args.output:
                save_nets([net], args.output.with_name(f"{args.output.stem}-fold{k}.npz"))
            rows += rate(args.cache, [net], [s["id"] for s in songs_of(FOLDS[k])])
        if args.json:
            args.json.write_text(json.dumps(rows, indent=1))
        summary(rows, sets)
    elif args.command == "summary":
        summary([r for path in args.rows for r in json.loads(path.read_text())], sets)
    elif args.command == "train":
        seen = [s["id"] for s in songs_of(SEEN)]
        nets = [fit(args.cache, seen, replace(settings, seed=seed)) for seed in args.seeds]
        save_nets(nets, args.output or Path("beatnet.npz"))
    else:
        nets = load_nets(args.net) if args.net else load_nets()
        features(args.cache, (args.set,))
        summary(rate(args.cache, nets, [s["id"] for s in songs_of((args.set,))]), sets)


if __name__ == "__main__":
    main()
