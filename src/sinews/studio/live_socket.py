"""The websocket behind dragging: the page asks for frames, the server steps the dancer live.

Messages from the page are JSON:

- ``{"op": "start", "dancer": ID, "genes": {"stiffness": 0.7, …}}`` — take the
  stage dancer live (with the sliders' genes); answered ``{"op": "ready"}``.
- ``{"op": "step", "frame": K, "grab": null | {"node": I, "x": X, "y": Y}}`` —
  step to the audio clock's frame K, the grabbed node pulled toward (X, Y)
  metres; answered with binary float32 ``[K, x0, y0, x1, y1, …, fx0, fy0, …]``
  (positions in metres, then the net force on each node in newtons).

A bad message is answered ``{"op": "error", "error": "<one line>"}`` and the
socket stays open.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from starlette.websockets import WebSocket, WebSocketDisconnect

from sinews.errors import SinewsError
from sinews.studio.live import Grab, LiveDancer
from sinews.studio.motion import SLIDER_GENES
from sinews.studio.service import Worker
from sinews.studio.validate import RequestError, json_object, number, whole

__all__ = ["live"]

_METRES = 100.0
"""How far from the origin a grab target may be."""


async def live(socket: WebSocket) -> None:
    """Serve one page's live stage dancer until it disconnects."""
    session = _Session(socket.app.state.worker)
    await socket.accept()
    try:
        while True:
            message = await socket.receive()
            if message["type"] == "websocket.disconnect":
                return
            try:
                await session.answer(socket, json_object(message))
            except SinewsError as exc:
                await socket.send_json({"op": "error", "error": str(exc)})
    except WebSocketDisconnect:
        return


class _Session:
    """One socket's live dancer."""

    def __init__(self, worker: Worker) -> None:
        self.worker = worker
        self.dancer: LiveDancer | None = None

    async def answer(self, socket: WebSocket, request: dict[str, Any]) -> None:
        if request.get("op") == "start":
            self.dancer = await _start(self.worker, request)
            await socket.send_json({"op": "ready", "frames": self.dancer.frames})
        elif request.get("op") == "step":
            dancer = self.dancer
            if dancer is None:
                raise RequestError("send a start message first")
            frame = whole(request.get("frame"), "frame", 0, 10**7)
            grab = _grab(request.get("grab"), dancer.n_nodes)
            await socket.send_bytes(await self.worker.run(lambda s: _step(dancer, frame, grab)))
        else:
            raise RequestError("op must be 'start' or 'step'")


async def _start(worker: Worker, request: dict[str, Any]) -> LiveDancer:
    dancer_id = whole(request.get("dancer"), "dancer", 0, 2**62)
    genes = request.get("genes") or {}
    if not isinstance(genes, dict) or not set(genes) <= set(SLIDER_GENES):
        raise RequestError(f"genes must map some of {', '.join(SLIDER_GENES)} to numbers")
    values = {name: number(v, name, 0.0, 1.0) for name, v in genes.items()}
    return await worker.run(lambda s: LiveDancer(s.motion.stage_dancer(dancer_id, values)))


def _grab(value: object, n_nodes: int) -> Grab | None:
    if value is None:
        return None
    if not isinstance(value, dict):
        raise RequestError("grab must be null or {node, x, y}")
    return Grab(
        node=whole(value.get("node"), "node", 0, n_nodes - 1),
        target=(
            number(value.get("x"), "x", -_METRES, _METRES),
            number(value.get("y"), "y", -_METRES, _METRES),
        ),
    )


def _step(dancer: LiveDancer, frame: int, grab: Grab | None) -> bytes:
    dancer.step_to(frame, grab)
    head = np.array([dancer.frame], dtype=np.float32)
    body = [dancer.positions.ravel(), dancer.forces.astype(np.float32).ravel()]
    return np.concatenate([head, *body]).astype("<f4").tobytes()
