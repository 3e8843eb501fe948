"""Scripted players for headless runs: what a person might do, frame by frame.

Each script is a `Script`: called with the latest `SceneFrame`, it returns
the input for the next step. They keep a little state (where a drag
started, which stroke is next) and make every random choice with their own
`numpy.random.Generator`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from sinews.scenes.kitten import KITTEN_NODES
from sinews.scenes.kittens import KittenAvalanche
from sinews.scenes.messages import NO_INPUT, SceneFrame, SceneInput

__all__ = ["Drawing", "KittenFlinger", "PushSequence", "preset_curves"]

Point = tuple[float, float]


@dataclass(frozen=True)
class PushSequence:
    """Hold the arrow keys for given spans of time (Falling for You).

    Attributes:
        pushes: (start, stop, push) seconds and direction, -1 left to 1 right.
    """

    pushes: tuple[tuple[float, float, float], ...]

    def __call__(self, frame: SceneFrame) -> SceneInput:
        """Push while the frame's time is in a span."""
        for start, stop, push in self.pushes:
            if start <= frame.time < stop:
                return SceneInput(push=push)
        return NO_INPUT


class Drawing:
    """Draw curves onto the page, one at each given time (Scribbles).

    Args:
        strokes: (time, curve) pairs, curve (P, 2) metres, in time order.
    """

    def __init__(self, strokes: list[tuple[float, npt.NDArray[np.float64]]]) -> None:
        self._strokes = list(strokes)

    def __call__(self, frame: SceneFrame) -> SceneInput:
        """The next stroke once its time has come."""
        if self._strokes and frame.time >= self._strokes[0][0]:
            _, curve = self._strokes.pop(0)
            return SceneInput(stroke=tuple((float(x), float(y)) for x, y in curve))
        return NO_INPUT


def preset_curves(screen: tuple[float, float, float, float]) -> list[npt.NDArray[np.float64]]:
    """Four hand-drawn-looking curves placed on a page: a wave, a spiral, a zigzag, a loop.

    Args:
        screen: (x_min, y_min, x_max, y_max) metres of the page.

    Returns:
        (P, 2) curves, metres.
    """
    x0, y0, x1, y1 = screen
    w, h = x1 - x0, y1 - y0
    t = np.linspace(0.0, 1.0, 90)
    shrink = 1.0 - 0.6 * t
    turn = 4.0 * np.pi * t
    unit = [
        np.stack([0.12 + 0.25 * t, 0.7 + 0.06 * np.sin(6 * np.pi * t)], axis=1),
        np.stack([0.6 + 0.11 * np.cos(turn) * shrink, 0.72 + 0.15 * np.sin(turn) * shrink], axis=1),
        np.stack([0.7 + 0.23 * t, 0.3 + 0.12 * np.abs((4 * t) % 2 - 1)], axis=1),
        np.stack([0.3 + 0.12 * np.cos(turn / 2), 0.3 + 0.1 * np.sin(turn / 2) + 0.12 * t], axis=1),
    ]
    return [np.array([x0, y0]) + curve * [w, h] for curve in unit]


class KittenFlinger:
    """Every few seconds, grab a node of a kitten on screen and drag it off the side.

    The node is chosen in turn from the back, the head, the tail tip and a
    paw, so each run shows how differently each resists.

    Args:
        scene: the kittens scene (to know which nodes make which kitten).
        rng: which kitten, and which way to throw it.
        every: seconds between grabs.
        drag_time: seconds the pointer takes to reach its goal off-screen.
    """

    PARTS = ("back", "head", "tail_tip", "front_paw")

    def __init__(
        self,
        scene: KittenAvalanche,
        rng: np.random.Generator,
        *,
        every: float = 1.5,
        drag_time: float = 0.5,
    ) -> None:
        self.scene = scene
        self.rng = rng
        self.every = every
        self.drag_time = drag_time
        self._next = 1.5
        self._turn = 0
        self._drag: tuple[float, npt.NDArray[np.float64], npt.NDArray[np.float64]] | None = None

    def __call__(self, frame: SceneFrame) -> SceneInput:
        """Press on a node, pull it off-screen, let go."""
        if self._drag is None and frame.time >= self._next:
            self._drag = self._start(frame)
        if self._drag is None:
            return NO_INPUT
        start_time, start, goal = self._drag
        progress = (frame.time - start_time) / self.drag_time
        if progress >= 1.0:
            self._drag = None
            self._next = frame.time + self.every
            return SceneInput(pointer=_point(goal), pressed=False)
        pointer = start + (goal - start) * progress**2  # speeding up: a fling
        return SceneInput(pointer=_point(pointer), pressed=True)

    def _start(
        self, frame: SceneFrame
    ) -> tuple[float, npt.NDArray[np.float64], npt.NDArray[np.float64]] | None:
        out = np.flatnonzero(self.scene.on_screen)
        if out.size == 0:
            return None
        kitten = int(self.rng.choice(out))
        part = self.PARTS[self._turn % len(self.PARTS)]
        self._turn += 1
        node = self.scene.parts[kitten].nodes.start + KITTEN_NODES.index(part)
        start = frame.positions[node].astype(np.float64)
        x0, _, x1, y1 = self.scene.screen
        side = x1 + 1.5 if start[0] > 0.5 * (x0 + x1) else x0 - 1.5
        goal = np.array([side, min(start[1] + 1.5, y1)])
        return (frame.time, start, goal)


def _point(xy: npt.NDArray[np.float64]) -> Point:
    return (float(xy[0]), float(xy[1]))
