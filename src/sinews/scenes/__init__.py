"""The seed-000 prototypes as playable scenes on the spring-mass engine.

Falling for You (ragdolls in love), Oh No, Kitten Avalanche! (fling the
kittens) and Scribbles (drawings that come alive). Each scene is ONE merged
`Body` holding all its creatures and pre-allocated spare parts, stepped on
the same engine as the dancers; game logic switches springs, attraction
pairs and nodes between steps. Drive a scene live with
``scene.step(SceneInput(...))`` (one 60 Hz frame, returns a `SceneFrame`),
or headless with ``scene.record(seconds, script)``.

Example:
    >>> import numpy as np
    >>> from sinews.scenes import FallingForYou, SceneInput
    >>> scene = FallingForYou(np.random.default_rng(0))
    >>> frame = scene.step(SceneInput(push=1.0))  # the right arrow key
    >>> frame.positions.shape == (scene.world.n_nodes, 2)
    True
"""

from __future__ import annotations

from sinews.scenes.catalog import SCENE_NAMES, make_scene, player
from sinews.scenes.falling import FallingForYou, FallingTuning
from sinews.scenes.grab import Pull
from sinews.scenes.kittens import KittenAvalanche
from sinews.scenes.messages import NO_INPUT, SceneEvent, SceneFrame, SceneInput, SceneRun, Script
from sinews.scenes.romance import RomanceTuning
from sinews.scenes.scene import Scene
from sinews.scenes.scribbles import Scribbles
from sinews.scenes.video import save_scene

__all__ = [
    "NO_INPUT",
    "SCENE_NAMES",
    "FallingForYou",
    "FallingTuning",
    "KittenAvalanche",
    "Pull",
    "RomanceTuning",
    "Scene",
    "SceneEvent",
    "SceneFrame",
    "SceneInput",
    "SceneRun",
    "Scribbles",
    "Script",
    "make_scene",
    "player",
    "save_scene",
]
