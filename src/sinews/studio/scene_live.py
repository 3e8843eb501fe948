"""A seed-000 scene played live for one page: stepped with the player's input, packed per frame.

The page draws what `LiveScene.header` describes once (names, springs,
radii, colours, node shapes, the scene's look) and then one binary frame per
step (`pack`), little-endian:

- 8 float32: frame number, score, camera x, camera y (metres), the last
  input message the frame has seen (its ``seq``), the grabbed node (-1: none),
  the scene's gauge (see `LiveScene.gauge`; NaN: none), flags (+1: forces follow,
  +2: paused, the scene will not move until it is resumed);
- N × 2 float32 node positions, metres;
- N × 2 float32 net forces, newtons (only with the debug overlay);
- N uint8 node visibility, then E uint8 spring visibility.

It also times itself: `costs` holds the milliseconds each step and each
packing took since it was last emptied.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from sinews.scenes import (
    FallingForYou,
    KittenAvalanche,
    Scene,
    SceneEvent,
    SceneFrame,
    SceneInput,
    Scribbles,
    make_scene,
)
from sinews.scenes.video import LOOKS

__all__ = ["HEAD_FLOATS", "Costs", "LiveScene"]

HEAD_FLOATS = 8
"""float32 values before the positions in a packed frame."""


@dataclass
class Costs:
    """Milliseconds spent per frame since the last report.

    Attributes:
        step: each `Scene.step`.
        pack: each packed frame.
    """

    step: list[float] = field(default_factory=list)
    pack: list[float] = field(default_factory=list)

    def report(self) -> dict[str, dict[str, float]]:
        """Median and largest of each, then forget them."""
        summary = {
            name: {
                "median": float(np.median(values)) if values else 0.0,
                "max": max(values, default=0.0),
            }
            for name, values in (("step", self.step), ("pack", self.pack))
        }
        self.step, self.pack = [], []
        return summary


class LiveScene:
    """One scene stepped on demand (use it from one thread).

    Args:
        name: one of `sinews.scenes.SCENE_NAMES`.
        seed: the scene's generator (the same seed as ``sinews scene --seed``
            gives the same scene); re-rolled tendons draw from a second one.
    """

    def __init__(self, name: str, seed: int) -> None:
        self.scene: Scene = make_scene(name, np.random.default_rng(seed), record_forces=True)
        self.rerolls = np.random.default_rng([seed, 1])
        self.last: SceneFrame = self.scene.frame()
        self.seq = 0
        self.costs = Costs()

    def header(self) -> dict[str, Any]:
        """What the page needs once to draw every frame (JSON)."""
        scene = self.scene
        layout = scene.world.layout
        body = layout.body
        look = LOOKS[scene.name]
        return {
            "scene": scene.name,
            "scoreName": scene.score_name,
            "viewSize": list(scene.view_size),
            "fps": 1.0 / scene.world.frame_dt,
            "names": list(body.names),
            "edges": body.edges.tolist(),
            "radii": [round(float(r), 4) for r in body.radius],
            "colors": [] if body.colors is None else body.colors.tolist(),
            "shapes": list(layout.node_shapes),
            "focus": self.focus(),
            "look": {
                "background": look.background,
                "floor": bool(look.floor),
                "floorColor": look.floor_color,
                "groundColor": look.ground_color,
                "edgeWidth": look.edge_width,
                "textColor": look.text_color,
            },
        }

    def focus(self) -> list[int]:
        """Nodes of the player's creature (the main doll the camera follows), if there is one."""
        scene = self.scene
        if not isinstance(scene, FallingForYou):
            return []
        return list(range(scene.dolls[0].nodes.start, scene.dolls[0].nodes.stop))

    def scribbles(self) -> dict[str, list[int]]:
        """Scribbles' live scribbles by id (as JSON keys), each its node indices; else empty."""
        scene = self.scene
        if not isinstance(scene, Scribbles):
            return {}
        return {str(k): s.nodes.tolist() for k, s in scene.scribbles.items()}

    def advance(self, inputs: list[tuple[SceneInput, int]]) -> list[SceneEvent]:
        """Step once per (input, seq of the last input message it reflects); return the events."""
        events: list[SceneEvent] = []
        for inp, seq in inputs:
            started = time.perf_counter()
            self.last = self.scene.step(inp)
            self.costs.step.append(1e3 * (time.perf_counter() - started))
            self.seq = seq
            events += self.last.events
        return events

    def news(self, events: list[SceneEvent]) -> dict[str, Any] | None:
        """The ``events`` message for the page (with the live scribbles), or None if none."""
        if not events:
            return None
        return {
            "op": "events",
            "step": self.last.step,
            "events": [[e.kind, list(e.ids)] for e in events],
            "scribbles": self.scribbles(),
        }

    def reroll(self, scribble: int) -> dict[str, Any] | None:
        """New tendons for a scribble and the news of it; None if there is no such scribble."""
        scene = self.scene
        if not isinstance(scene, Scribbles) or scribble not in scene.scribbles:
            return None
        scene.regenerate_tendons(scribble, self.rerolls)
        return self.news([SceneEvent("tendons", (scribble,))])

    def pack(self, *, forces: bool, paused: bool = False) -> bytes:
        """The latest frame as the page's binary frame (see the module docstring).

        Args:
            forces: add the net forces (debug overlay).
            paused: flag the frame as paused.
        """
        started = time.perf_counter()
        frame = self.last
        with_forces = forces and frame.forces is not None
        head = np.array(
            [
                frame.step,
                frame.score,
                *frame.camera,
                self.seq,
                -1 if frame.grabbed is None else frame.grabbed,
                self.gauge(),
                int(with_forces) + 2 * int(paused),
            ],
            dtype="<f4",
        )
        assert head.size == HEAD_FLOATS
        parts = [head.tobytes(), frame.positions.astype("<f4").tobytes()]
        if with_forces and frame.forces is not None:
            parts.append(np.nan_to_num(frame.forces).astype("<f4").tobytes())
        parts += [
            frame.node_visible.astype(np.uint8).tobytes(),
            frame.edge_visible.astype(np.uint8).tobytes(),
        ]
        packed = b"".join(parts)
        self.costs.pack.append(1e3 * (time.perf_counter() - started))
        return packed

    def gauge(self) -> float:
        """The scene's gauge, NaN if it has none.

        Kittens: seconds between arrivals (the difficulty ramp). Falling for You:
        the strongest held hand's pull as a share of the pull that breaks it.
        """
        scene = self.scene
        if isinstance(scene, KittenAvalanche):
            return scene.interval
        if isinstance(scene, FallingForYou):
            pulls = scene.romance.link_tension(scene.world).values()
            return max(pulls, default=0.0) / scene.romance.tuning.break_force
        return math.nan
