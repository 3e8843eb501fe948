// The stage: one dancer large, with the debug overlay, and dragging.
//
// It plays the dancer's recorded dance at the clock's frame. Grabbing a node
// hands the dancer to the server's live simulation (LiveLink): each animation
// frame the page asks for the clock's frame with the node pulled toward the
// mouse, and draws the answer. It stays live until another dancer is shown.

import { cameraTrack, drawDancer, extent, forceScale, paints, pose, toPx, view } from "./draw.js";

const GRAB_PIXELS = 14;

export class Stage {
  /**
   * @param {HTMLCanvasElement} canvas
   * @param {import("./live.js").LiveLink} link
   * @param {{play: function(): Promise, onLive: function(boolean)}} hooks
   */
  constructor(canvas, link, hooks) {
    this.canvas = canvas;
    this.link = link;
    this.hooks = hooks;
    this.pack = null;
    this.overlay = false;
    this.live = null; // {frame, positions, forces} from the server once a node was grabbed
    this.grab = null; // {node, px: [x, y]} while the mouse holds a node
    this.v = null;
    canvas.addEventListener("pointerdown", (event) => this.press(event));
    canvas.addEventListener("pointermove", (event) => this.move(event));
    canvas.addEventListener("pointerup", () => this.release());
    canvas.addEventListener("pointercancel", () => this.release());
  }

  /** Match the canvas's pixels to its size on screen. */
  resize() {
    const ratio = window.devicePixelRatio || 1;
    const box = this.canvas.getBoundingClientRect();
    this.canvas.width = Math.max(1, Math.round(box.width * ratio));
    this.canvas.height = Math.max(1, Math.round(box.height * ratio));
    if (this.pack) this.forceScale = forceScale(this.pack.arrays.forces.data, this.canvas.width);
  }

  /** Show a decoded stage pack (a dancer with forces and triggers); ends any live drag. */
  show(pack, genes) {
    const { header, arrays } = pack;
    const frames = header.frames;
    const nodes = header.names.length;
    const data = arrays.positions.data;
    this.pack = pack;
    this.genes = genes;
    this.paint = paints(header);
    this.track = cameraTrack(data, 1, 0, frames, nodes, header.fps);
    this.room = extent(data, 1, 0, frames, nodes, header.radii, this.track);
    this.forceScale = forceScale(arrays.forces.data, Math.min(this.canvas.width, this.canvas.height));
    this.endLive();
  }

  endLive() {
    this.live = null;
    this.grab = null;
    this.camera = null;
    this.link.stop();
    this.hooks.onLive(false);
  }

  /** Pointer position in canvas pixels. */
  pixels(event) {
    const box = this.canvas.getBoundingClientRect();
    return [
      ((event.clientX - box.left) * this.canvas.width) / box.width,
      ((event.clientY - box.top) * this.canvas.height) / box.height,
    ];
  }

  async press(event) {
    if (!this.pack || !this.v || !this.shown) return;
    const [x, y] = this.pixels(event);
    let best = null;
    this.pack.header.radii.forEach((r, i) => {
      const [nx, ny] = toPx(this.v, this.shown[2 * i], this.shown[2 * i + 1]);
      const d = Math.hypot(nx - x, ny - y);
      if (d <= Math.max(GRAB_PIXELS, r * this.v.scale + 6) && (!best || d < best.d)) best = { i, d };
    });
    if (!best) return;
    event.preventDefault();
    this.canvas.setPointerCapture(event.pointerId);
    this.grab = { node: best.i, px: [x, y] };
    this.canvas.classList.add("dragging");
    await this.hooks.play();
    try {
      await this.link.start(this.pack.header.id, this.genes);
      if (!this.live) this.live = { frame: -1, positions: this.shown, forces: null };
      this.hooks.onLive(true);
    } catch {
      this.grab = null;
    }
  }

  move(event) {
    if (this.grab) this.grab.px = this.pixels(event);
  }

  release() {
    this.grab = null;
    this.canvas.classList.remove("dragging");
  }

  /** The grab in world metres, or null. */
  target() {
    if (!this.grab || !this.v) return null;
    const [px, py] = this.grab.px;
    return { node: this.grab.node, x: this.v.left + px / this.v.scale, y: this.v.top - py / this.v.scale };
  }

  /** Draw the stage dancer at ``frame`` (live: ask the server for that frame too). */
  draw(frame) {
    if (!this.pack) return;
    const { header, arrays } = this.pack;
    const nodes = header.names.length;
    const t = Math.min(Math.max(frame, 0), header.frames - 1);
    let xy;
    let forces;
    if (this.live) {
      if (this.link.ready && !this.link.busy) {
        this.link.step(t, this.target()).then((reply) => {
          if (reply && this.live) this.live = reply;
        });
      }
      xy = this.live.positions;
      forces = this.live.forces;
      let centre = 0;
      for (let i = 0; i < nodes; i++) centre += xy[2 * i] / nodes;
      this.camera = this.camera === null ? centre : this.camera + 0.04 * (centre - this.camera);
    } else {
      xy = pose(arrays.positions.data, 1, t * nodes * 2, nodes);
      forces = arrays.forces.data.subarray(t * nodes * 2, (t + 1) * nodes * 2);
      this.camera = null;
    }
    this.shown = xy;
    const x = this.camera ?? this.track[t];
    this.v = view(this.canvas, this.live ? this.liveRoom(xy, x) : this.room, x);
    const g = this.canvas.getContext("2d");
    drawDancer(g, this.v, header, this.paint, xy, this.overlay ? this.overlayAt(t, forces) : null);
    if (this.grab) this.drawPull(g);
  }

  /** The recorded dance's room, grown to hold the live pose. */
  liveRoom(xy, x) {
    const room = { ...this.room };
    this.pack.header.radii.forEach((r, i) => {
      room.top = Math.max(room.top, xy[2 * i + 1] + r);
      room.half = Math.max(room.half, Math.abs(xy[2 * i] - x) + r);
    });
    return room;
  }

  overlayAt(t, forces) {
    const { header, arrays } = this.pack;
    const count = header.triggerNodes.length;
    const fired = [];
    for (let r = 0; r < count; r++) {
      if (arrays.triggers.data[t * count + r]) fired.push(header.triggerNodes[r]);
    }
    return { names: header.names, forces, forceScale: this.forceScale, fired };
  }

  drawPull(g) {
    const i = this.grab.node;
    const [x0, y0] = toPx(this.v, this.shown[2 * i], this.shown[2 * i + 1]);
    const [x1, y1] = this.grab.px;
    g.save();
    g.setLineDash([6, 4]);
    g.strokeStyle = "rgb(60,90,200)";
    g.lineWidth = 2;
    g.beginPath();
    g.moveTo(x0, y0);
    g.lineTo(x1, y1);
    g.stroke();
    g.restore();
  }
}
