"""A dancer run's settings: a song, a dance length and the common evolution settings.

A run file or options give ``song`` (``demo:groove`` or a path) and
``seconds`` beside `EvolutionConfig`'s keys; the song's file and SHA-256 go
into the run's columns, so resuming or re-simulating can check the song is
still the same. A run's tempo correction (``bpm``) and beat shift (``beat_shift``, a
fraction of a beat), both set in the studio, are part of its settings too: every replay
analyses the song at that tempo and moves its beats by that shift.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

from sinews.errors import SinewsError
from sinews.experiments.dancers.score import DEFAULT_WEIGHTS
from sinews.experiments.run_config import EvolutionConfig, build_config
from sinews.files import atomic_path
from sinews.music.demo import DEMO_NAMES, write_demo

__all__ = ["DEFAULTS", "DEFAULT_SECONDS", "DEMO_PREFIX", "NAME", "dancer_config", "song_path"]

NAME = "dancers"
"""The kind's name, and the stored kind of its runs."""
DEMO_PREFIX = "demo:"
DEFAULT_SECONDS = 30.0
"""Default dance length: 30 s, or the whole song if it is shorter."""

DEFAULTS: dict[str, Any] = {
    "population": 16,
    "generations": 20,
    "seed": 0,
    "fitness": ["beat-lift", "smoothness", "liveliness", "humanoid", "on-stage", "variety"],
    "weights": {},
    "phase_in": {"start": 5, "full": 15},
    "strategy": "ga",
    "song": None,
    "seconds": None,
}
"""Settings of a dancer run when neither the run file nor an option gives them."""


def dancer_config(
    *, file_values: Mapping[str, Any], options: Mapping[str, Any]
) -> tuple[EvolutionConfig, str, float | None]:
    """A dancer run's settings from a run file and command-line options.

    Returns:
        The common config, the song (``demo:NAME`` or a path) and the dance
        length in seconds (None: 30 s or the whole song if shorter).

    Raises:
        SinewsError: no song, or a bad setting.
    """
    config, extra = build_config(
        file_values=file_values,
        options=options,
        defaults=DEFAULTS,
        term_defaults=DEFAULT_WEIGHTS,
        kind_keys=("song", "seconds"),
    )
    if not extra["song"]:
        raise SinewsError("give a song: --song FILE or --song demo:groove")
    seconds = extra["seconds"]
    if seconds is not None:
        if isinstance(seconds, bool) or not isinstance(seconds, int | float) or not seconds > 0:
            raise SinewsError(f"seconds must be a positive number, got {seconds!r}")
        seconds = float(seconds)
    return config, str(extra["song"]), seconds


def song_path(song: str) -> Path:
    """The file of a song setting; a demo song is written to the app's data dir once."""
    if not song.startswith(DEMO_PREFIX):
        return Path(song).expanduser().resolve()
    name = song[len(DEMO_PREFIX) :]
    if name not in DEMO_NAMES:
        raise SinewsError(f"no demo song {name!r}; choose from {', '.join(DEMO_NAMES)}")
    import platformdirs

    path = Path(platformdirs.user_data_dir("sinews")) / "songs" / f"{name}.wav"
    if not path.is_file():
        path.parent.mkdir(parents=True, exist_ok=True)
        with atomic_path(path) as tmp:
            write_demo(name, tmp)
    return path
