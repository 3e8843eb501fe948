"""A GP run's settings: the task, the rates, the primitives (seed 003), one dataclass.

A run of kind ``"gp-<figure>"`` stores, beside the common settings
(`EvolutionConfig`: population, generations, seed, fitness spec, strategy
``gp`` with `GPVariation` options), the task's name and options, the trial
length, the physics and control rates, the function set and the range of the
ephemeral random constants: `GPSettings`. How a simulation runs on this
machine (threads, recording) is not stored; it is `Runtime`.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from functools import cached_property
from typing import Any

from sinews.control.gp import BASIC_FUNCTIONS, PrimitiveSet, Program, parse_program
from sinews.errors import SinewsError
from sinews.evolve import GenomeSpace
from sinews.experiments.figures import heard_song
from sinews.figures.tasks import Task, make_task
from sinews.limits import MAX_PHYSICS_HZ, check_whole
from sinews.music.features import MusicFeatures

__all__ = ["GPSettings", "Runtime"]


@dataclass(frozen=True)
class GPSettings:
    """What a GP run's programs are and how they are simulated (stored with the run).

    Attributes:
        task_name: the task (see `sinews.figures.tasks.TASKS`), e.g. ``"luxo-hop"``.
        task_options: what it was built with (`Task.params`), e.g. ``{"target": 1.5}``.
        seconds: trial length (None: the task's own).
        control_hz: program evaluations per simulated second.
        physics_hz: physics steps per simulated second.
        functions: the function set.
        erc_range: the range of the ephemeral random constants.
        song_path: the song file a dance hears (None: no song).
        song_hash: its SHA-256, checked whenever the song is read again.
    """

    task_name: str
    task_options: Mapping[str, Any]
    seconds: float | None = None
    control_hz: int = 100
    physics_hz: int = 1000
    functions: tuple[str, ...] = BASIC_FUNCTIONS
    erc_range: tuple[float, float] = (-1.0, 1.0)
    song_path: str | None = None
    song_hash: str | None = None

    @classmethod
    def from_values(cls, values: Mapping[str, Any]) -> GPSettings:
        """Settings from a run's config (see `to_dict`), checked.

        Raises:
            SinewsError: an unknown task or function, or a bad number, naming the setting.
        """
        try:
            low, high = (float(v) for v in values["erc_range"])
            settings = cls(
                task_name=str(values["task"]),
                task_options=dict(values["task_options"]),
                seconds=None if values["seconds"] is None else float(values["seconds"]),
                control_hz=check_whole("control_hz", values["control_hz"], 1, MAX_PHYSICS_HZ),
                physics_hz=check_whole("physics_hz", values["physics_hz"], 1, MAX_PHYSICS_HZ),
                functions=tuple(str(f) for f in values["functions"]),
                erc_range=(low, high),
                song_path=_optional_text(values.get("song_path")),
                song_hash=_optional_text(values.get("song_hash")),
            )
        except (KeyError, TypeError, ValueError):
            raise SinewsError("malformed GP run settings") from None
        if settings.seconds is not None and not settings.seconds > 0:
            raise SinewsError("seconds must be positive")
        if settings.physics_hz % settings.control_hz:
            raise SinewsError("control_hz must divide physics_hz")
        _ = settings.pset  # an unknown function or bad constants fail here
        if bool(settings.task.music) != (settings.song_path is not None):
            raise SinewsError("a dance needs a song (--song), and only a dance hears one")
        return settings

    def to_dict(self) -> dict[str, Any]:
        """The settings as stored in a run's config."""
        return {
            "task": self.task_name,
            "task_options": dict(self.task_options),
            "seconds": self.seconds,
            "control_hz": self.control_hz,
            "physics_hz": self.physics_hz,
            "functions": list(self.functions),
            "erc_range": list(self.erc_range),
            "song_path": self.song_path,
            "song_hash": self.song_hash,
        }

    @cached_property
    def task(self) -> Task:
        """The task, built from its name and options (and the trial length, if set)."""
        length = {} if self.seconds is None else {"seconds": self.seconds}
        return make_task(self.task_name, **self.task_options, **length)

    @cached_property
    def pset(self) -> PrimitiveSet:
        """The run's primitives: the task's terminals, the functions, the constants."""
        return PrimitiveSet(self.task.terminals, functions=self.functions,
                            erc_range=self.erc_range)  # fmt: skip

    @cached_property
    def music(self) -> MusicFeatures | None:
        """The song's analysis (None without a song).

        Raises:
            SinewsError: the song cannot be read, or has changed since the run started.
        """
        return None if self.song_path is None else heard_song(self.song_path, self.song_hash)

    @property
    def genomes(self) -> GenomeSpace:
        """The run's programs: its primitives, one tree per driven joint."""
        return GenomeSpace(pset=self.pset, n_trees=len(self.task.joints))

    def parse(self, texts: Sequence[str]) -> list[Program]:
        """Stored S-expressions as programs of this run."""
        return [parse_program(text, self.pset) for text in texts]


def _optional_text(value: object) -> str | None:
    return None if value is None else str(value)


@dataclass(frozen=True)
class Runtime:
    """How programs are simulated here and now (never stored: results do not depend on it).

    Attributes:
        nthread: MuJoCo threads (None: every CPU).
        parallel_interpreter: evaluate programs with the parallel kernel (off:
            on 2 cores it doubled a generation's time; see `sinews.benchmarks.gp`).
        record_hz: frame rate of recorded motion.
    """

    nthread: int | None = None
    parallel_interpreter: bool = False
    record_hz: float = 60.0
