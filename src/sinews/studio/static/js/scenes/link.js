// The live link of a scene page: one websocket on which the server plays the scene at
// 60 fps (see sinews.studio.scene_socket). The page sends the input as it changes and
// reads back frames, events and the server's timings; it measures two round trips
// itself: a ping's, and an input's (sent until a frame that has seen it arrives).

import { openSocket } from "../api.js";
import { decodeFrame, FrameBuffer } from "./frames.js";

const PING_MS = 1000;
const SAMPLES = 60;

const median = (values) => {
  if (!values.length) return NaN;
  const sorted = [...values].sort((a, b) => a - b);
  return sorted[Math.floor(sorted.length / 2)];
};

export class SceneLink {
  /**
   * @param {{scene: function(object), events: function(object), error: function(string),
   *   closed: function()}} on what to do with the scene's header, its events, a one-line
   *   error and a lost link
   */
  constructor(on) {
    this.on = on;
    this.socket = null;
    this.header = null;
    this.frames = null;
    this.seq = 0;
    this.sent = new Map(); // seq -> when it was sent
  }

  /** Play scene ``name`` from ``seed`` (closing any other scene's link). */
  async start(name, seed) {
    this.close();
    const attempt = (this.attempt = {});
    this.seq = 0;
    this.sent.clear();
    this.timing = { server: null, ping: [], input: [], arrivals: [] };
    const socket = await openSocket(`/api/scenes/${name}`, {
      message: (data) => this.receive(data),
      close: () => {
        if (this.socket === socket) {
          this.socket = null;
          this.on.closed();
        }
      },
    });
    if (attempt !== this.attempt) {
      socket.close(); // another scene was asked for meanwhile
      return;
    }
    this.socket = socket;
    this.send({ op: "start", seed });
    this.pinger = setInterval(() => this.send({ op: "ping", t: performance.now() }), PING_MS);
  }

  close() {
    clearInterval(this.pinger);
    const socket = this.socket;
    this.socket = null;
    this.header = null;
    this.frames = null;
    if (socket) socket.close();
  }

  send(message) {
    if (this.socket && this.socket.readyState === WebSocket.OPEN) this.socket.send(JSON.stringify(message));
  }

  /** Send input (``input``: {push, pointer, pressed} or {points} for a stroke). */
  input(op, input) {
    this.seq += 1;
    this.sent.set(this.seq, performance.now());
    this.send({ op, seq: this.seq, ...input });
  }

  receive(data) {
    if (typeof data !== "string") {
      if (!this.header) return;
      const frame = decodeFrame(data, this.header.names.length, this.header.edges.length);
      this.frames.push(frame);
      this.measure(frame);
      return;
    }
    const message = JSON.parse(data);
    if (message.op === "scene") {
      this.header = message;
      this.frames = new FrameBuffer(message.fps);
      this.on.scene(message);
    } else if (message.op === "events") this.on.events(message);
    else if (message.op === "stats") this.timing.server = message;
    else if (message.op === "pong") keep(this.timing.ping, performance.now() - message.t);
    else if (message.op === "error") this.on.error(message.error);
  }

  measure(frame) {
    keep(this.timing.arrivals, frame.arrived);
    for (const [seq, when] of this.sent) {
      if (seq > frame.seq) break;
      keep(this.timing.input, frame.arrived - when);
      this.sent.delete(seq);
    }
  }

  /** Milliseconds, medians of the latest samples: {step, pack, late, ping, input, fps}. */
  summary() {
    const { server, ping, input, arrivals } = this.timing;
    const span = arrivals.length > 1 ? arrivals[arrivals.length - 1] - arrivals[0] : NaN;
    return {
      step: server ? server.step.median : NaN,
      stepMax: server ? server.step.max : NaN,
      pack: server ? server.pack.median : NaN,
      late: server ? server.late : 0,
      ping: median(ping),
      input: median(input),
      fps: (1000 * (arrivals.length - 1)) / span,
    };
  }
}

function keep(samples, value) {
  samples.push(value);
  if (samples.length > SAMPLES) samples.shift();
}
