"""The scenes by name, and the scripted player each is shown with headless."""

from __future__ import annotations

import numpy as np

from sinews.errors import SinewsError
from sinews.scenes.falling import FallingForYou
from sinews.scenes.kittens import KittenAvalanche
from sinews.scenes.messages import Script
from sinews.scenes.scene import Scene
from sinews.scenes.scribbles import Scribbles
from sinews.scenes.scripts import Drawing, KittenFlinger, PushSequence, preset_curves

__all__ = ["SCENE_NAMES", "make_scene", "player"]

_SCENES: dict[str, type[FallingForYou] | type[KittenAvalanche] | type[Scribbles]] = {
    "falling-for-you": FallingForYou,
    "kittens": KittenAvalanche,
    "scribbles": Scribbles,
}
SCENE_NAMES: tuple[str, ...] = tuple(_SCENES)
"""Names the CLI and studio know the scenes by."""


def make_scene(name: str, rng: np.random.Generator, *, record_forces: bool = False) -> Scene:
    """A scene in its default size.

    Args:
        name: one of `SCENE_NAMES`.
        rng: everything random in it.
        record_forces: keep the net forces per frame (debug overlay).
    """
    if name not in _SCENES:
        raise SinewsError(f"no scene called {name!r}; choose from {', '.join(SCENE_NAMES)}")
    return _SCENES[name](rng, record_forces=record_forces)


def player(scene: Scene, rng: np.random.Generator) -> Script:
    """A scripted player for ``scene``.

    Kittens: grab a node of a kitten every 1.5 s and drag it off-screen.
    Scribbles: draw four preset curves, one every 1.5 s. Falling for You:
    push the main doll right from 7 to 9 s (enough to part a couple).

    Args:
        scene: what `make_scene` made.
        rng: the player's own choices.
    """
    if isinstance(scene, KittenAvalanche):
        return KittenFlinger(scene, rng)
    if isinstance(scene, Scribbles):
        curves = preset_curves(scene.screen)
        return Drawing([(1.5 * k, curve) for k, curve in enumerate(curves)])
    return PushSequence(((7.0, 9.0, 1.0),))
