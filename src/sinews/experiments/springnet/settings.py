"""A spring-net run's settings (seed 001): the figure, the trial, the net, the rates."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from functools import cached_property
from typing import Any

import numpy as np
import numpy.typing as npt

from sinews.control.music_input import BeatClock, MusicInput, beat_clock, music_table
from sinews.control.protocol import Controller
from sinews.control.springnet import SpringNetController
from sinews.errors import SinewsError
from sinews.evolve.alton import SpringNetEncoding
from sinews.experiments.figures import FIGURES, heard_song, make_figure
from sinews.experiments.springnet.dance import (
    DANCE_FIGURES,
    DRIVE,
    DRIVE_FORCE,
    MAX_DRIVE_FORCE,
    drive_weights,
)
from sinews.figures import Figure
from sinews.figures.tasks import Task, make_task
from sinews.limits import MAX_MASSES, MAX_PHYSICS_HZ, MAX_SECONDS, check_whole
from sinews.music.features import MusicFeatures

__all__ = [
    "CLOCKS", "MAX_TEMPI", "NET_TIME_STEP", "PHYSICS_HZ", "TERMS", "SpringNetSettings", "tempi_of",
]  # fmt: skip

FloatArray = npt.NDArray[np.float64]

NET_TIME_STEP = 0.005
"""The nets' own time step, seconds (stable for every net of up to ~60 masses)."""
PHYSICS_HZ = {"snake": 500, "luxo": 1000, "humanoid": 1000}
"""Default physics rate per figure: the snake's distances at 500 Hz match 1 kHz (r = 0.996
over 2000 random nets); the Luxo's hops are chaotic, so it keeps its model's 1 kHz."""
MAX_TEMPI = 4
"""At most this many playback rates per dance (each one is a whole rollout)."""
TERMS = {"distance": 1.0}
"""The fitness terms and their weights: the paper's distance only."""
CLOCKS = ("time", "beats")
"""A dancing net's time: the song's seconds, or its beats (`BeatClock`)."""


@dataclass(frozen=True)
class SpringNetSettings:
    """How a run's nets are simulated.

    Attributes:
        figure: the figure's name (see `FIGURES`).
        seconds: trial length.
        masses: n, masses per net.
        physics_hz: physics steps per second.
        control_hz: controller ticks per second (divides ``physics_hz``).
        task: ``"dance"`` for nets entrained by a song (see
            `sinews.experiments.springnet.dance`), or None for the paper's distance.
        song_path: a dance's song file.
        song_hash: its SHA-256, checked whenever the song is read again.
        tempi: a dance's playback rates, 1.0 (the song as it is) first: every net dances
            the song at each rate (`MusicFeatures.played_at`) and its terms are the means,
            so a net that swings at one period of its own cannot score on all of them.
        drive: a dance's largest drive weight (force per unit of music): how hard the
            beat may push the masses against the springs.
        clock: a dance's net time (`CLOCKS`): ``"time"``, the song's seconds, or
            ``"beats"``, one beat = 0.5 s of the net's (`BeatClock`), so the net's own
            swings keep their ratio to the beat at any tempo.
    """

    figure: str
    seconds: float
    masses: int
    physics_hz: int
    control_hz: int = 100
    task: str | None = None
    song_path: str | None = None
    song_hash: str | None = None
    tempi: tuple[float, ...] = (1.0,)
    drive: float = DRIVE_FORCE
    clock: str = "time"

    @classmethod
    def from_values(cls, values: Mapping[str, Any]) -> SpringNetSettings:
        """Settings from run-file/option/config values, defaults filled per figure.

        Raises:
            SinewsError: an unknown figure or a bad number, naming the setting.
        """
        figure = values.get("figure")
        if figure not in FIGURES:
            raise SinewsError(f"no figure called {figure!r}; choose from {', '.join(FIGURES)}")
        if figure not in PHYSICS_HZ:
            raise SinewsError(f"spring nets drive the {', '.join(PHYSICS_HZ)}; evolve the "
                              f"{figure} with --controller gp")  # fmt: skip
        dancing = values.get("task") == "dance" and figure in DANCE_FIGURES
        joints = make_task(DANCE_FIGURES[figure]).joints if dancing else make_figure(figure).joints
        masses = values.get("masses") or max(4, len(joints))
        settings = cls(
            figure=figure,
            seconds=_number(values.get("seconds"), "seconds", MAX_SECONDS),
            masses=check_whole("masses", masses, 2, MAX_MASSES),
            physics_hz=check_whole(
                "physics_hz", values.get("physics_hz") or PHYSICS_HZ[figure], 1, MAX_PHYSICS_HZ
            ),
            control_hz=check_whole("control_hz", values.get("control_hz"), 1, MAX_PHYSICS_HZ),
            task=values.get("task"),
            song_path=values.get("song_path"),
            song_hash=values.get("song_hash"),
            tempi=tempi_of(values.get("tempi")),
            drive=_drive(values.get("drive")),
            clock=values.get("clock") or "time",
        )
        if settings.physics_hz % settings.control_hz:
            raise SinewsError("control_hz must divide physics_hz")
        if settings.task not in (None, "dance"):
            raise SinewsError(f"spring nets have no task {settings.task!r}; only dance")
        if settings.task is not None and figure not in DANCE_FIGURES:
            raise SinewsError(f"spring nets dance only the {', '.join(DANCE_FIGURES)}")
        if (settings.task is None) != (settings.song_path is None):
            raise SinewsError("a dance needs a song (--song), and only a dance hears one")
        if settings.task is None and settings.tempi != (1.0,):
            raise SinewsError("tempi are for a dance (--task dance)")
        if settings.task is None and settings.drive != DRIVE_FORCE:
            raise SinewsError("a drive is for a dance (--task dance)")
        if settings.clock not in CLOCKS:
            raise SinewsError(f"clock must be one of {', '.join(CLOCKS)}, got {settings.clock!r}")
        if settings.task is None and settings.clock != "time":
            raise SinewsError("a beat clock is for a dance (--task dance)")
        return settings

    def to_dict(self) -> dict[str, Any]:
        """The settings as stored in a run's config."""
        return {
            "figure": self.figure,
            "seconds": self.seconds,
            "masses": self.masses,
            "physics_hz": self.physics_hz,
            "control_hz": self.control_hz,
            "task": self.task,
            "song_path": self.song_path,
            "song_hash": self.song_hash,
            **(
                {}
                if self.task is None
                else {"tempi": list(self.tempi), "drive": self.drive, "clock": self.clock}
            ),
        }

    @cached_property
    def dance(self) -> Task | None:
        """The dance the nets are rated by (None: the paper's distance)."""
        if self.task is None:
            return None
        return make_task(DANCE_FIGURES[self.figure], seconds=self.seconds)

    @cached_property
    def simulated_figure(self) -> Figure:
        """The figure the nets drive: a dance's (with the sites its terms read) or the plain
        one (a site has no mass: the motion is the same)."""
        return make_figure(self.figure) if self.dance is None else self.dance.figure

    @cached_property
    def music(self) -> MusicFeatures | None:
        """The song's analysis (None without a song); see `heard_song`."""
        return None if self.song_path is None else heard_song(self.song_path, self.song_hash)

    @property
    def terms(self) -> dict[str, float]:
        """The fitness terms and their full weights."""
        return TERMS if self.dance is None else dict(self.dance.weights)

    @property
    def genome_size(self) -> int:
        """Genes per net: the net's, then (for a dance) its drive weights."""
        drive = 0 if self.task is None else self.masses * len(DRIVE)
        return self.encoding.size + drive

    @property
    def encoding(self) -> SpringNetEncoding:
        """Where masses, springs and positions sit in a gene vector."""
        return SpringNetEncoding(self.masses)

    def driven(self, figure: Figure) -> npt.NDArray[np.intp]:
        """(J,) the actuators the nets drive: all, or a dance's joints (the others hold
        their neutral angles)."""
        return np.arange(figure.n_actuators) if self.dance is None else self.dance.actuators

    def outputs(self, figure: Figure) -> npt.NDArray[np.intp]:
        """(J,) the mass each driven actuator follows: the k-th driven one mass k mod n."""
        return np.arange(len(self.driven(figure))) % self.masses

    def controller(self, figure: Figure, genes: FloatArray) -> SpringNetController:
        """The controller of (P, G) genes driving ``figure`` (a dance's reads sensors and
        music: see `with_music`); an actuator it does not drive has gain 0."""
        low, high = figure.joint_range[:, 0], figure.joint_range[:, 1]
        driven = self.driven(figure)
        gain = np.zeros(figure.n_actuators)
        gain[driven] = np.where(np.isfinite(high - low), 0.5 * (high - low), 1.0)[driven]
        outputs = np.zeros(figure.n_actuators, dtype=np.intp)
        outputs[driven] = self.outputs(figure)
        size = self.encoding.size
        drive = None
        if self.task is not None:
            drive = drive_weights(genes[:, size:], self.masses, figure.n_sensors, self.drive)
        return SpringNetController(
            self.encoding.decode(genes[:, :size]),
            outputs=outputs,
            gain=gain,
            offset=figure.neutral,
            ts=NET_TIME_STEP,
            input_weights=drive,
        )

    def heard_at(self, rate: float) -> MusicFeatures:
        """The song's analysis played at ``rate`` (one of `tempi`).

        Raises:
            SinewsError: not a dance, or the song played at ``rate`` is shorter than a trial.
        """
        if self.music is None:
            raise SinewsError("only a dance hears a song")
        music = self.music if rate == 1.0 else self.music.played_at(rate)
        if music.duration + 1e-9 < self.seconds:
            raise SinewsError(f"the song played {rate:g}x as fast lasts {music.duration:.1f} s, "
                              f"less than a {self.seconds:g} s trial")  # fmt: skip
        return music

    def with_music(self, controller: SpringNetController, rate: float = 1.0) -> Controller:
        """The controller hearing the song played at ``rate`` (for a dance; on the beat
        clock if the run's is ``"beats"``), else itself."""
        if self.music is None:
            return controller
        heard, ticks = self.heard_at(rate), round(self.seconds * self.control_hz)
        inner: Controller = controller
        if self.clock == "beats":
            inner = BeatClock(controller, beat_clock(heard, self.control_hz, ticks),
                              self.control_hz)  # fmt: skip
        return MusicInput(inner, music_table(heard, self.control_hz, ticks), self.control_hz)


def tempi_of(value: object) -> tuple[float, ...]:
    """Playback rates from a run file (a list), ``--tempi 0.8,1.25`` or a stored config,
    with 1.0 (the song as it is) put first: each 0.5-2, at most `MAX_TEMPI` in all."""
    if value is None:
        return (1.0,)
    items = value.split(",") if isinstance(value, str) else value
    if not isinstance(items, list | tuple) or not items:
        raise SinewsError(f"tempi must be playback rates, e.g. 0.8,1.25; got {value!r}")
    try:
        rates = [float(item) for item in items]
    except (TypeError, ValueError):
        raise SinewsError(f"tempi must be playback rates, e.g. 0.8,1.25; got {value!r}") from None
    if not all(0.5 <= rate <= 2.0 for rate in rates):
        raise SinewsError(f"tempi must be between 0.5 and 2, got {value!r}")
    tempi = tuple(dict.fromkeys([1.0, *rates]))
    if len(tempi) > MAX_TEMPI:
        raise SinewsError(f"at most {MAX_TEMPI} tempi (the song's own among them)")
    return tempi


def _drive(value: object) -> float:
    """A dance's largest drive weight from a run file, ``--drive`` or a stored config
    (`DRIVE_FORCE` when not given)."""
    if value is None:
        return DRIVE_FORCE
    return _number(value, "drive", MAX_DRIVE_FORCE)


def _number(value: object, name: str, most: float) -> float:
    """``value`` as a float in (0, most]; else a one-line `SinewsError`."""
    if isinstance(value, bool) or not isinstance(value, int | float) or not 0 < value <= most:
        raise SinewsError(f"{name} must be a number above 0 and at most {most:g}, got {value!r}")
    return float(value)
