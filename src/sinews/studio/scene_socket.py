"""The websocket behind the scene pages: the server plays a scene at 60 fps, the page sends input.

``/api/scenes/{name}`` (``name`` one of `sinews.scenes.SCENE_NAMES`). The
page's messages are JSON objects:

- ``{"op": "start", "seed": S}`` — a fresh scene; answered ``{"op": "scene", …}``
  (`LiveScene.header`), then a binary frame (`sinews.studio.scene_live`)
  every 1/60 s until the socket closes;
- ``{"op": "input", "seq": K, "push": P, "pointer": [x, y] | null, "pressed": B}``
  — the keys and mouse as they are now (``push`` −1…1, the arrow keys;
  metres); a press shorter than a frame still grabs for one frame;
- ``{"op": "stroke", "seq": K, "points": [[x, y], …]}`` — a finished drawing
  (Scribbles only; 2 to `MAX_STROKE_POINTS` points);
- ``{"op": "reroll", "scribble": ID}`` — new tendons for that scribble;
- ``{"op": "overlay", "on": B}`` — frames carry forces (debug overlay);
- ``{"op": "pause", "on": B}`` — stop or resume stepping;
- ``{"op": "ping", "t": T}`` — answered ``{"op": "pong", "t": T}`` at once
  (``T`` a number, the page's clock in milliseconds).

The server also sends ``{"op": "events", "step": K, "events": [[kind, [ids]], …],
"scribbles": {id: [nodes]}}`` when something happened, and ``{"op": "stats",
"step": {"median", "max"}, "pack": {…}, "late": L}`` (milliseconds per frame,
frames dropped because the server fell behind) once a second. A bad message
is answered ``{"op": "error", "error": "<one line>"}`` and the socket stays open.
Steps run on the studio's worker thread, like everything else.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
from collections import deque
from collections.abc import Callable, Coroutine
from typing import Any

from starlette.routing import BaseRoute, WebSocketRoute
from starlette.websockets import WebSocket, WebSocketState

from sinews.errors import SinewsError
from sinews.scenes import SCENE_NAMES, SceneInput
from sinews.studio.scene_live import LiveScene
from sinews.studio.service import Worker
from sinews.studio.validate import RequestError, flag, json_object, number, point, whole

__all__ = ["MAX_LIVE_SCENES", "MAX_STROKE_POINTS", "scene_routes"]

MAX_LIVE_SCENES = 4
"""Scene sockets served at once (each costs the worker 60 steps a second)."""
MAX_STROKE_POINTS = 2000
MAX_WAITING_STROKES = 8
"""Strokes received but not yet drawn (one is drawn per frame)."""
"""Most points in one drawn stroke."""
_METRES = 100.0
"""How far from the origin a pointer or stroke point may be."""
_FPS = 60.0
_MOST_BEHIND = 4
"""Frames stepped at once to catch up; further behind, the scene skips the lost time."""
_log = logging.getLogger(__name__)


def scene_routes() -> list[BaseRoute]:
    """The scene websocket route, with its own count of live scenes."""
    live = [0]

    async def scene_socket(socket: WebSocket) -> None:
        name = socket.path_params["name"]
        if name not in SCENE_NAMES or live[0] >= MAX_LIVE_SCENES:
            await socket.close(code=1008)
            return
        live[0] += 1
        try:
            await socket.accept()
            await _Session(socket, socket.app.state.worker, name).serve()
        finally:
            live[0] -= 1

    return [WebSocketRoute("/api/scenes/{name}", scene_socket)]


class _Session:
    """One page's scene: the input as it stands, and the task that steps and sends frames."""

    def __init__(self, socket: WebSocket, worker: Worker, name: str) -> None:
        self.socket = socket
        self.worker = worker
        self.name = name
        self.scene: LiveScene | None = None
        self.ticker: asyncio.Task[None] | None = None
        self.sending = asyncio.Lock()
        self.held = SceneInput()
        self.seq = 0
        self.pressed_once = False
        self.strokes: deque[tuple[tuple[float, float], ...]] = deque()
        self.overlay = False
        self.paused = False
        self.dirty = False

    async def serve(self) -> None:
        """Answer messages until the page goes away."""
        try:
            while True:
                message = await self.socket.receive()
                if message["type"] == "websocket.disconnect":
                    break
                try:
                    await self.answer(json_object(message))
                except SinewsError as exc:
                    await self.send(self.socket.send_json, {"op": "error", "error": str(exc)})
        finally:
            if self.ticker is not None:
                self.ticker.cancel()
                with contextlib.suppress(asyncio.CancelledError):
                    await self.ticker

    async def send(self, how: Callable[[Any], Coroutine[Any, Any, None]], what: Any) -> None:
        """Send one message (frames and answers come from two tasks)."""
        async with self.sending:
            await how(what)

    async def answer(self, request: dict[str, Any]) -> None:
        op = request.get("op")
        if op == "start":
            await self.start(whole(request.get("seed"), "seed", 0, 2**32 - 1))
        elif op == "ping":
            t = number(request.get("t"), "t", 0.0, 1e12)
            await self.send(self.socket.send_json, {"op": "pong", "t": t})
        elif self.scene is None:
            raise RequestError("send a start message first")
        elif op == "input":
            self.take_input(request)
        elif op == "stroke":
            self.take_stroke(request)
        elif op == "reroll":
            await self.reroll(whole(request.get("scribble"), "scribble", 0, 2**62))
        elif op == "overlay":
            self.overlay = flag(request.get("on"), "on")
            self.dirty = True
        elif op == "pause":
            self.paused = flag(request.get("on"), "on")
            self.dirty = True  # the page learns from a frame that the scene stands still
        else:
            raise RequestError(
                "op must be one of start, input, stroke, reroll, overlay, pause, ping"
            )

    async def start(self, seed: int) -> None:
        if self.ticker is not None:
            self.ticker.cancel()
            with contextlib.suppress(asyncio.CancelledError):
                await self.ticker
        self.scene = scene = await self.worker.run(lambda s: LiveScene(self.name, seed))
        self.held, self.pressed_once, self.paused = SceneInput(), False, False
        self.strokes.clear()
        header = await self.worker.run(lambda s: scene.header())
        await self.send(self.socket.send_json, {"op": "scene", "seed": seed, **header})
        self.ticker = asyncio.create_task(self.tick(scene))

    def take_input(self, request: dict[str, Any]) -> None:
        seq = whole(request.get("seq"), "seq", 0, 2**24)
        pointer = request.get("pointer")
        pressed = flag(request.get("pressed"), "pressed")
        self.held = SceneInput(
            push=number(request.get("push"), "push", -1.0, 1.0),
            pointer=None if pointer is None else point(pointer, "pointer", _METRES),
            pressed=pressed,
        )
        self.pressed_once |= pressed
        self.seq = seq

    def take_stroke(self, request: dict[str, Any]) -> None:
        if self.name != "scribbles":
            raise RequestError("only Scribbles takes drawings")
        seq = whole(request.get("seq"), "seq", 0, 2**24)
        if len(self.strokes) >= MAX_WAITING_STROKES:
            raise RequestError("strokes are coming faster than the scene can draw them")
        points = request.get("points")
        if not isinstance(points, list) or not 2 <= len(points) <= MAX_STROKE_POINTS:
            raise RequestError(f"points must be a list of 2 to {MAX_STROKE_POINTS} [x, y] pairs")
        self.strokes.append(tuple(point(p, "point", _METRES) for p in points))
        self.seq = seq

    async def reroll(self, scribble: int) -> None:
        scene = self.scene
        assert scene is not None
        news = await self.worker.run(lambda s: scene.reroll(scribble))
        if news is None:
            raise RequestError(f"no scribble {scribble}")
        await self.send(self.socket.send_json, news)
        self.dirty = True

    def inputs(self, count: int) -> list[tuple[SceneInput, int]]:
        """Input for the next ``count`` frames: held keys and mouse, a short press, one stroke."""
        held = self.held
        first = SceneInput(
            push=held.push,
            pointer=held.pointer,
            pressed=held.pressed or self.pressed_once,
            stroke=self.strokes.popleft() if self.strokes else None,
        )
        self.pressed_once = False
        return [(first, self.seq)] + [(held, self.seq)] * (count - 1)

    async def tick(self, scene: LiveScene) -> None:
        """Send frames until the page goes away; a failing scene closes the socket (1011)."""
        try:
            await self.frames(scene)
        except Exception:
            if self.socket.client_state != WebSocketState.CONNECTED:
                return  # the page went away mid-send
            _log.exception("scene %s failed", self.name)
            await self.socket.close(code=1011)

    async def play(self, scene: LiveScene, count: int) -> tuple[dict[str, Any] | None, bytes]:
        """Step ``count`` frames (none if paused) on the worker; the news and the packed frame."""
        paused, forces = self.paused, self.overlay
        inputs = [] if paused else self.inputs(count)
        return await self.worker.run(
            lambda s: (
                scene.news(scene.advance(inputs)),
                scene.pack(forces=forces, paused=paused),
            )
        )

    async def frames(self, scene: LiveScene) -> None:
        """Step and send a frame every 1/60 s (skipping lost time when far behind)."""
        loop = asyncio.get_running_loop()
        due = loop.time()
        sent = late = 0
        while True:
            due += 1.0 / _FPS
            await asyncio.sleep(max(0.0, due - loop.time()))
            behind = int((loop.time() - due) * _FPS)
            due += behind / _FPS
            if behind >= _MOST_BEHIND:
                late, behind = late + behind, 0
            if self.paused and not self.dirty:
                continue
            self.dirty = False
            news, frame = await self.play(scene, 1 + behind)
            if news is not None:
                await self.send(self.socket.send_json, news)
            await self.send(self.socket.send_bytes, frame)
            sent += 1
            if sent % round(_FPS) == 0:
                stats = await self.worker.run(lambda s: scene.costs.report())
                await self.send(self.socket.send_json, {"op": "stats", **stats, "late": late})
                late = 0
