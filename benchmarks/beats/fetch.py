"""Fetch the beat corpus's audio from Debian packages and cut the excerpts.

    python benchmarks/beats/fetch.py [--cache DIR]

For each package in corpus.toml: `apt-get download PACKAGE=VERSION` and `dpkg-deb -x`
into DIR (default: $SINEWS_BEATS_CACHE or ~/.cache/sinews-beats), then each excerpt is
cut with ffmpeg to DIR/excerpts/ID.wav (44.1 kHz, mono, 16-bit). Files already there are
kept. A file given as ARCHIVE!MEMBER is read from inside a zip archive (nexuiz-music's
music.pk3). Needs apt-get, dpkg-deb and ffmpeg; runs with any Python >= 3.11 (no sinews import).
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tomllib
import zipfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
SETS = (
    "tune",
    "heldout",
    "confirm",
    "confirm2",
    "confirm3",
    "confirm4",
    "confirm5",
    "confirm6",
    "confirm7",
    "confirm8",
    "confirm9",
    "confirm10",
    "confirm11",
    "confirm12",
    "confirm13",
    "confirm14",
)
"""The corpus's sets, in the order they were fixed (docs/beats.md)."""
SEEN = SETS[:-1]
"""Every set but the newest, which is kept unseen for one final score."""

REFERENCE_TRACKERS = ("madmom", "essentia", "librosa")
"""The trackers whose consensus makes the reference beats (make_reference.py)."""
PAIR_COLUMNS = {
    "F_mad_ess": ("madmom", "essentia"),
    "F_mad_lib": ("madmom", "librosa"),
    "F_ess_lib": ("essentia", "librosa"),
}
"""reference/summary.tsv's columns of F between two reference trackers."""


def default_cache() -> Path:
    return Path(os.environ.get("SINEWS_BEATS_CACHE", Path.home() / ".cache" / "sinews-beats"))


def load_corpus() -> tuple[float, list[dict]]:
    with open(HERE / "corpus.toml", "rb") as fh:
        corpus = tomllib.load(fh)
    return float(corpus["duration"]), corpus["song"]


def in_set(song: dict, name: str) -> bool:
    """Whether ``song`` is in the set ``name``; "all" is every seen set (`SEEN`)."""
    return song["set"] in SEEN if name == "all" else song["set"] == name


def excerpt_path(cache: Path, song_id: str) -> Path:
    return cache / "excerpts" / f"{song_id}.wav"


def fetch(cache: Path) -> None:
    duration, songs = load_corpus()
    debs = cache / "debs"
    tree = cache / "tree"
    debs.mkdir(parents=True, exist_ok=True)
    (cache / "excerpts").mkdir(parents=True, exist_ok=True)
    for package, version in sorted({(s["package"], s["version"]) for s in songs}):
        marker = tree / f".{package}_{version}"
        if marker.exists():
            continue
        deb = next(debs.glob(f"{package}_*.deb"), None)
        if deb is None:
            print(f"downloading {package}={version}", file=sys.stderr)
            subprocess.run(["apt-get", "download", f"{package}={version}"], cwd=debs, check=True)
            deb = next(debs.glob(f"{package}_*.deb"))
        subprocess.run(["dpkg-deb", "-x", str(deb), str(tree)], check=True)
        marker.touch()
    for song in songs:
        out = excerpt_path(cache, song["id"])
        if out.exists():
            continue
        source = _source(tree, song["file"])
        subprocess.run(
            [
                "ffmpeg",
                "-nostdin",
                "-v",
                "error",
                "-ss",
                str(song["start"]),
                "-t",
                str(duration),
                "-i",
                str(source),
                "-ac",
                "1",
                "-ar",
                "44100",
                "-c:a",
                "pcm_s16le",
                str(out),
            ],
            check=True,
        )
        print(f"cut {out.name}", file=sys.stderr)


def _source(tree: Path, file: str) -> Path:
    """The file to cut: ``PATH`` in the package tree, or ``ARCHIVE!MEMBER`` of a zip (a .pk3).

    A member is extracted once, next to its archive.
    """
    if "!" not in file:
        return tree / file
    archive, member = file.split("!", 1)
    out = tree / f"{archive}.members" / member
    if not out.exists():
        out.parent.mkdir(parents=True, exist_ok=True)
        with zipfile.ZipFile(tree / archive) as zf:
            out.write_bytes(zf.read(member))
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cache", type=Path, default=default_cache())
    fetch(parser.parse_args().cache)


if __name__ == "__main__":
    main()
