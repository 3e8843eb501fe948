// The live link for dragging: a websocket on which the server steps the stage
// dancer to the clock's frame, pulling the grabbed node toward the mouse.

import { openSocket } from "./api.js";

export class LiveLink {
  /** @param {function(string)} onError shows a one-line error */
  constructor(onError) {
    this.onError = onError;
    this.socket = null;
    this.ready = null;
    this.pending = null; // resolver of the step in flight
    this.key = null;
  }

  /** Take dancer ``id`` (with ``genes``) live; resolves when the server is ready. */
  start(id, genes) {
    const key = JSON.stringify([id, genes]);
    if (this.key === key && this.ready) return this.ready;
    this.key = key;
    this.ready = this.open().then(
      (socket) =>
        new Promise((resolve, reject) => {
          this.onReady = resolve;
          this.onFail = reject;
          socket.send(JSON.stringify({ op: "start", dancer: id, genes }));
        }),
    );
    this.ready.catch(() => {
      this.key = null;
      this.ready = null;
    });
    return this.ready;
  }

  open() {
    if (this.socket && this.socket.readyState === WebSocket.OPEN) return Promise.resolve(this.socket);
    const opening = openSocket("/api/live", {
      message: (data) => this.receive(data),
      close: () => {
        this.socket = null;
        this.key = null;
        this.ready = null;
      },
    });
    return opening.then((socket) => (this.socket = socket));
  }

  receive(data) {
    if (typeof data === "string") {
      const message = JSON.parse(data);
      if (message.op === "ready") this.onReady(message);
      if (message.op === "error") {
        this.onError(message.error);
        if (this.onFail) this.onFail(new Error(message.error));
        if (this.pending) this.pending(null);
        this.pending = null;
      }
      return;
    }
    const values = new Float32Array(data);
    const nodes = (values.length - 1) / 4;
    const reply = {
      frame: values[0],
      positions: values.subarray(1, 1 + 2 * nodes),
      forces: values.subarray(1 + 2 * nodes),
    };
    if (this.pending) this.pending(reply);
    this.pending = null;
  }

  /** Whether a step is waiting for its answer (the page asks again only after it). */
  get busy() {
    return this.pending !== null;
  }

  /** Step to ``frame`` with ``grab`` ({node, x, y} or null); resolves to positions and forces. */
  step(frame, grab) {
    return new Promise((resolve) => {
      this.pending = resolve;
      this.socket.send(JSON.stringify({ op: "step", frame, grab }));
    });
  }

  /** Forget the live dancer (the next start makes a new one). */
  stop() {
    this.key = null;
    this.ready = null;
  }
}
