"""What goes into a scene each frame (`SceneInput`) and what comes out (`SceneFrame`).

These are the messages a live driver (the studio, over its websocket)
exchanges with a scene at 60 frames per second; a headless run collects the
frames into a `SceneRun`.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from sinews.trajectory import Trajectory

__all__ = ["NO_INPUT", "SceneEvent", "SceneFrame", "SceneInput", "SceneRun", "Script"]

Point = tuple[float, float]


@dataclass(frozen=True)
class SceneInput:
    """The player's input for one frame.

    Attributes:
        push: horizontal push of the arrow keys, -1 (left) to 1 (right).
        pointer: where the mouse is, world metres (x, y), or None if off the stage.
        pressed: whether the mouse button is held; a press grabs the nearest
            node, a release lets it go (flings it).
        stroke: a curve the player has just finished drawing, world metres,
            or None (Scribbles turns it into a creature).
    """

    push: float = 0.0
    pointer: Point | None = None
    pressed: bool = False
    stroke: tuple[Point, ...] | None = None


NO_INPUT = SceneInput()
"""No keys, no mouse: the scene plays itself."""


class SceneEvent(NamedTuple):
    """Something that happened in a frame.

    Attributes:
        kind: e.g. ``"link"``, ``"balloon"``, ``"baby"``, ``"break"``
            (Falling for You), ``"spawn"``, ``"flung"``, ``"wandered"`` (kittens),
            ``"scribble"``, ``"tendons"`` (Scribbles).
        ids: the creatures involved, by the scene's creature index.
    """

    kind: str
    ids: tuple[int, ...]


@dataclass(frozen=True, eq=False)
class SceneFrame:
    """A scene after one step: everything a live view needs to draw it.

    Attributes:
        step: frames simulated so far.
        time: seconds simulated so far.
        positions: (N, 2) float32 metres of every node (hidden ones too).
        node_visible: (N,) which nodes to draw.
        edge_visible: (E,) which springs to draw.
        camera: (x, y) metres the view is centred on.
        score: the scene's counter (kittens flung, couples formed, scribbles alive).
        events: what happened during the step.
        grabbed: the node the mouse holds, or None.
        forces: (N, 2) float32 net newtons that moved each node into this
            frame (debug overlay), or None when the scene does not record them.
    """

    step: int
    time: float
    positions: npt.NDArray[np.float32]
    node_visible: npt.NDArray[np.bool_]
    edge_visible: npt.NDArray[np.bool_]
    camera: Point
    score: int
    events: tuple[SceneEvent, ...] = ()
    grabbed: int | None = None
    forces: npt.NDArray[np.float32] | None = None


Script = Callable[[SceneFrame], SceneInput]
"""Scripted play: given the latest frame, the input for the next step."""


@dataclass(frozen=True, eq=False)
class SceneRun:
    """A headless run of a scene.

    Attributes:
        scene: the scene's name, e.g. ``"kittens"``.
        score_name: what ``score`` counts.
        trajectory: every frame, with per-frame visibility (and forces if recorded).
        camera: (T, 2) metres the view is centred on in each frame.
        view_size: (width, height) metres the view shows.
        score: (T,) the scene's counter in each frame.
        events: (frame, event) for everything that happened, in order.
    """

    scene: str
    score_name: str
    trajectory: Trajectory
    camera: npt.NDArray[np.float64]
    view_size: tuple[float, float]
    score: npt.NDArray[np.int64]
    events: tuple[tuple[int, SceneEvent], ...]
