// Drawing a scene frame: the scene's look (sky, kitten room, paper), its bodies with
// hearts and spikes, the debug overlay, and the page's own marks (the player's doll, the
// selected scribble, the mouse's pull, a stroke being drawn). The view shows the scene's
// view size around its camera; the canvas has the same aspect.

import {
  drawFigure,
  drawFloor,
  drawForces,
  drawLabels,
  forceScale,
  paints,
  pixels,
  rgb,
  toPx,
} from "../draw.js";
import { spikeAnchors } from "../shapes.js";

const MARK = "rgb(212,86,42)";
const PULL = "rgb(60,90,200)";

export class ScenePainter {
  /** @param {HTMLCanvasElement} canvas */
  constructor(canvas) {
    this.canvas = canvas;
    this.header = null;
    this.v = null;
    this.px = null;
    this.forceScale = 0;
  }

  /** Get ready to draw the scene of ``header`` (the server's "scene" message). */
  setScene(header) {
    this.header = header;
    const { look, edges, radii, shapes } = header;
    this.figure = { edges, radii, shapes, anchors: spikeAnchors(edges, radii.length) };
    this.paint = paints(header);
    this.look = {
      background: rgb(look.background),
      ground: rgb(look.groundColor),
      floor: rgb(look.floorColor),
      ink: { text: rgb(look.textColor), halo: rgb(look.background) },
    };
    this.forceScale = 0;
    const [width, height] = header.viewSize;
    this.canvas.style.aspectRatio = `${width} / ${height}`;
    this.resize();
  }

  /** Match the canvas's pixels to its size on screen. */
  resize() {
    const ratio = window.devicePixelRatio || 1;
    const box = this.canvas.getBoundingClientRect();
    this.canvas.width = Math.max(1, Math.round(box.width * ratio));
    this.canvas.height = Math.max(1, Math.round(box.height * ratio));
  }

  /** The view: the scene's view size around ``camera``, fitted into the canvas. */
  view([x, y]) {
    const [width, height] = this.header.viewSize;
    const scale = Math.min(this.canvas.width / width, this.canvas.height / height);
    return {
      scale,
      left: x - this.canvas.width / (2 * scale),
      top: y + this.canvas.height / (2 * scale),
      width: this.canvas.width,
      height: this.canvas.height,
    };
  }

  /** Canvas pixels to world metres in the view last drawn. */
  toWorld([px, py]) {
    return [this.v.left + px / this.v.scale, this.v.top - py / this.v.scale];
  }

  /**
   * Draw ``shown`` (FrameBuffer.at()) with the page's ``marks``: {overlay, focus (nodes of the
   * player's creature), selected (nodes), pull ([x, y] pixels the grabbed node is pulled to),
   * stroke ([[x, y] pixels] being drawn)}.
   */
  draw(shown, marks) {
    const g = this.canvas.getContext("2d");
    const v = (this.v = this.view(shown.camera));
    const side = Math.min(v.width, v.height);
    const figure = this.figure;
    g.fillStyle = this.look.background;
    g.fillRect(0, 0, v.width, v.height);
    if (this.header.look.floor) drawFloor(g, v, this.look.ground, this.look.floor);
    else if (marks.focus.length) this.sky(g, v);
    const px = (this.px = pixels(v, shown.xy, figure.radii.length));
    const visible = { nodes: shown.nodeVisible, edges: shown.edgeVisible };
    if (marks.selected) this.halo(g, px, marks.selected, shown.nodeVisible);
    drawFigure(g, v, figure, this.paint, px, visible, this.header.look.edgeWidth);
    if (marks.focus.length) this.tag(g, px, marks.focus, side);
    if (marks.overlay && shown.forces) {
      const scale = forceScale(shown.forces, side);
      this.forceScale = this.forceScale ? 0.9 * this.forceScale + 0.1 * scale : scale;
      drawForces(g, px, shown.forces, this.forceScale, side, shown.nodeVisible);
    }
    if (marks.overlay) {
      const options = { visible: shown.nodeVisible, ink: this.look.ink, size: 0.016 };
      drawLabels(g, v, px, this.header.names, figure.radii, options);
    }
    if (marks.pull && shown.grabbed !== null) this.line(g, [px[shown.grabbed], marks.pull], PULL, [6, 4]);
    if (marks.stroke) this.line(g, marks.stroke, this.look.ink.text, []);
  }

  /** Faint dots a metre apart, so the sky shows how the camera moves. */
  sky(g, v) {
    const step = v.scale;
    const x0 = -(v.left % 1) * step;
    const y0 = (v.top % 1) * step;
    const r = Math.max(2, 0.01 * step);
    g.fillStyle = "rgba(255,255,255,0.9)";
    for (let x = x0 < 0 ? x0 + step : x0; x < v.width; x += step) {
      for (let y = y0 < 0 ? y0 + step : y0; y < v.height; y += step) {
        g.beginPath();
        g.arc(x, y, r, 0, 2 * Math.PI);
        g.fill();
      }
    }
  }

  /** A soft band under the selected scribble. */
  halo(g, px, nodes, visible) {
    const shown = nodes.filter((i) => visible[i]);
    if (!shown.length) return;
    g.save();
    g.strokeStyle = "rgba(255,190,60,0.45)";
    g.lineWidth = Math.max(8, 0.035 * this.v.scale);
    g.lineCap = g.lineJoin = "round";
    g.beginPath();
    shown.forEach((i, k) => (k ? g.lineTo : g.moveTo).call(g, ...px[i]));
    g.stroke();
    g.restore();
  }

  /** A small arrow above the player's creature. */
  tag(g, px, nodes, side) {
    const x = nodes.reduce((sum, i) => sum + px[i][0], 0) / nodes.length;
    const top = Math.min(...nodes.map((i) => px[i][1])) - 0.03 * side;
    const size = 0.018 * side;
    g.fillStyle = MARK;
    g.beginPath();
    g.moveTo(x, top);
    g.lineTo(x - size, top - 1.6 * size);
    g.lineTo(x + size, top - 1.6 * size);
    g.closePath();
    g.fill();
  }

  line(g, points, color, dash) {
    if (points.length < 2) return;
    g.save();
    g.setLineDash(dash);
    g.strokeStyle = color;
    g.lineWidth = 2;
    g.beginPath();
    points.forEach(([x, y], k) => (k ? g.lineTo(x, y) : g.moveTo(x, y)));
    g.stroke();
    g.restore();
  }

  /** The visible node whose disc is within ``reach`` pixels of ``[x, y]`` and nearest, or null. */
  nodeAt([x, y], visible, reach) {
    let best = null;
    this.figure.radii.forEach((r, i) => {
      if (!visible[i]) return;
      const d = Math.hypot(this.px[i][0] - x, this.px[i][1] - y) - r * this.v.scale;
      if (d <= reach && (!best || d < best.d)) best = { i, d };
    });
    return best && best.i;
  }
}
