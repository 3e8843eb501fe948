"""What the figure kinds share: the built-in figures, their fitness, hand-pick files.

A figure run's stored kind is ``"<controller>-<figure>"`` (e.g.
``"springnet-snake"``); each controller is a run kind of
`sinews.experiments.kinds`.

Spring-net runs (seed 001) are rated by the distance travelled,
``|x_final - x_initial|`` of the figure's root, in metres; GP runs (seed 003)
by a task's goal and style terms.
"""

from __future__ import annotations

import os
import re
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from sinews.errors import SinewsError
from sinews.experiments.dancers.settings import song_path
from sinews.figures import Figure, RolloutResult, humanoid, luxo, snake
from sinews.figures.humanoid3d import humanoid3d
from sinews.figures.luxo3d import luxo3d
from sinews.music.analysis import analyse_file
from sinews.music.features import MusicFeatures

__all__ = [
    "FIGURES",
    "dance_song",
    "distance_travelled",
    "heard_song",
    "make_figure",
    "parse_keep",
    "read_keep_file",
]

FIGURES: dict[str, Callable[[], Figure]] = {
    "snake": snake,
    "luxo": luxo,
    "humanoid": humanoid,
    "luxo3d": luxo3d,
    "humanoid3d": humanoid3d,
}
"""The built-in figures by name (``luxo3d`` and ``humanoid3d`` are 3D: a free root)."""


def make_figure(name: str) -> Figure:
    """The built-in figure called ``name``; `SinewsError` naming the choices otherwise."""
    if name not in FIGURES:
        raise SinewsError(f"no figure called {name!r}; choose from {', '.join(FIGURES)}")
    return FIGURES[name]()


def distance_travelled(result: RolloutResult) -> npt.NDArray[np.float64]:
    """(P,) the paper's fitness: ``|x_final - x_initial|`` of each figure's root, metres."""
    return np.abs(result.distance)


_KEEP_LINE = re.compile(r"^\s*(\d+)\s*:\s*([\d\s,]*)$")


def parse_keep(text: str, *, where: str = "keep file") -> dict[int, list[int]]:
    """Hand picks per generation from text like ``"0: 12 40\\n3: 7"``.

    One line per generation: its number, a colon, the indices of the
    individuals that must survive it (spaces or commas between them). Blank
    lines and ``#`` comments are ignored.

    Returns:
        generation → indices, in the order given.

    Raises:
        SinewsError: a malformed line, a generation given twice or a repeated index.
    """
    keep: dict[int, list[int]] = {}
    for number, raw in enumerate(text.splitlines(), start=1):
        line = raw.split("#", 1)[0].strip()
        if not line:
            continue
        match = _KEEP_LINE.match(line)
        if match is None:
            raise SinewsError(f"{where} line {number}: expected 'GENERATION: INDEX INDEX ...'")
        generation = int(match.group(1))
        indices = [int(i) for i in re.split(r"[\s,]+", match.group(2).strip()) if i]
        if generation in keep:
            raise SinewsError(f"{where} line {number}: generation {generation} given twice")
        if len(set(indices)) != len(indices):
            raise SinewsError(f"{where} line {number}: an index is repeated")
        keep[generation] = indices
    return keep


def read_keep_file(path: str | os.PathLike[str]) -> dict[int, list[int]]:
    """`parse_keep` of a file; `SinewsError` if it cannot be read."""
    try:
        text = Path(path).read_text(encoding="utf-8")
    except OSError as exc:
        raise SinewsError(f"{path}: cannot read ({exc.strerror or exc})") from None
    except UnicodeDecodeError:
        raise SinewsError(f"{path}: not a UTF-8 text file") from None
    return parse_keep(text, where=str(path))


def heard_song(path: str, song_hash: str | None) -> MusicFeatures:
    """The analysis (cached) of the song a figure's run dances to, checked against its hash.

    Raises:
        SinewsError: the song cannot be read, or has changed since the run started.
    """
    music = analyse_file(path)
    if song_hash is not None and music.song_hash != song_hash:
        raise SinewsError(f"{path}: the song has changed since the run started")
    return music


def dance_song(given: Mapping[str, Any]) -> tuple[Path, MusicFeatures] | None:
    """The song a run's ``song`` setting names, analysed (cached), or None without one.

    Raises:
        SinewsError: a song for a task other than a dance, a dance without one, or a
            song that cannot be read (one line, as everywhere).
    """
    dancing = given.get("task") == "dance"
    song = given.get("song")
    if not song:
        if dancing:
            raise SinewsError("a dance needs a song: --song FILE or --song demo:groove")
        return None
    if not dancing:
        raise SinewsError("--song is for the dance task (--task dance)")
    path = song_path(str(song))
    return path, analyse_file(path)


def dance_seconds(music: MusicFeatures, seconds: Any, default: float) -> Any:
    """A dance's length: ``seconds`` if given (not longer than the song; other checks are
    the run settings'), else ``default`` or the whole song if shorter.

    Raises:
        SinewsError: ``seconds`` is longer than the song.
    """
    if seconds is None:
        return min(default, music.duration)
    number = isinstance(seconds, int | float) and not isinstance(seconds, bool)
    if number and seconds > music.duration + 1e-9:
        raise SinewsError(f"the song is only {music.duration:.1f} s long; dance at most that")
    return seconds
