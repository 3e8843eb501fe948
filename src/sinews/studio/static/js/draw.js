// Drawing bodies on a canvas, in the look of sinews.render's FramePainter:
// discs (or hearts, or spikes) for nodes with a darker rim, tendons in the
// darkened mean colour of their ends, a ground line, and the debug overlay
// (labels, force arrows, rings on nodes whose responder fires). The dancer
// pages and the scene pages share these.

import { heartPath, spikePath } from "./shapes.js";

const BACKGROUND = "rgb(250,248,243)";
const GROUND = "rgb(232,228,219)";
const FLOOR = "rgb(120,114,104)";
const TEXT = "rgb(40,40,40)";
const ARROW = "rgb(214,39,40)";
const RING = "rgb(255,170,0)";

export const rgb = (c, f = 1) => `rgb(${Math.round(c[0] * f)},${Math.round(c[1] * f)},${Math.round(c[2] * f)})`;

/** Colours of one dancer, worked out once. */
export function paints(dancer) {
  const colors = dancer.colors.length ? dancer.colors : dancer.radii.map(() => [90, 120, 200]);
  return {
    node: colors.map((c) => rgb(c)),
    rim: colors.map((c) => rgb(c, 0.55)),
    edge: dancer.edges.map(([i, j]) =>
      rgb([0, 1, 2].map((k) => 0.5 * (colors[i][k] + colors[j][k])), 0.62),
    ),
  };
}

/** One frame's node positions in metres, (x0, y0, x1, y1, …), from a packed motion array. */
export function pose(data, scale, offset, nodes) {
  const out = new Float32Array(2 * nodes);
  for (let k = 0; k < 2 * nodes; k++) out[k] = data[offset + k] * scale;
  return out;
}

/**
 * Where a body is seen from, frame by frame: its mean x, averaged over about a second
 * either side, so the camera follows a travelling dancer without shaking.
 */
export function cameraTrack(data, scale, offset, frames, nodes, fps) {
  const centre = new Float64Array(frames);
  for (let t = 0; t < frames; t++) {
    let sum = 0;
    const base = offset + t * nodes * 2;
    for (let i = 0; i < nodes; i++) sum += data[base + 2 * i];
    centre[t] = (sum * scale) / nodes;
  }
  const half = Math.round(fps);
  const prefix = new Float64Array(frames + 1);
  for (let t = 0; t < frames; t++) prefix[t + 1] = prefix[t] + centre[t];
  const track = new Float32Array(frames);
  for (let t = 0; t < frames; t++) {
    const lo = Math.max(0, t - half);
    const hi = Math.min(frames, t + half + 1);
    track[t] = (prefix[hi] - prefix[lo]) / (hi - lo);
  }
  return track;
}

/**
 * How much room a dance needs most of the time: the 95th percentile over frames of its
 * top (highest node edge) and of its half width around the camera track, in metres,
 * within [0.5, 2.6] and [0.25, 1.4] (a dancer flinging a hand away may leave the picture).
 */
export function extent(data, scale, offset, frames, nodes, radii, track) {
  const tops = new Float32Array(frames);
  const halves = new Float32Array(frames);
  for (let t = 0; t < frames; t++) {
    const base = offset + t * nodes * 2;
    let top = 0;
    let half = 0;
    for (let i = 0; i < nodes; i++) {
      top = Math.max(top, data[base + 2 * i + 1] * scale + radii[i]);
      half = Math.max(half, Math.abs(data[base + 2 * i] * scale - track[t]) + radii[i]);
    }
    tops[t] = top;
    halves[t] = half;
  }
  const high = (values) => values.sort()[Math.floor(0.95 * (values.length - 1))];
  const clip = (value, lo, hi) => Math.min(Math.max(value, lo), hi);
  return { top: clip(high(tops), 0.5, 2.6), half: clip(high(halves), 0.25, 1.4) };
}

/**
 * A view with the floor near the bottom, room for ``room`` ({top, half} metres, see
 * extent()), centred on ``x``.
 */
export function view(canvas, room, x) {
  const low = -0.12;
  const scale = Math.min(
    canvas.height / (room.top + 0.12 - low),
    canvas.width / (2 * room.half + 0.16),
  );
  return {
    scale,
    left: x - canvas.width / (2 * scale),
    top: low + canvas.height / scale,
    width: canvas.width,
    height: canvas.height,
  };
}

export const toPx = (v, x, y) => [(x - v.left) * v.scale, (v.top - y) * v.scale];

/** The ground under y = 0: its colour, the floor line and marks every half metre. */
export function drawFloor(g, v, ground = GROUND, floor = FLOOR) {
  const [, y] = toPx(v, 0, 0);
  g.fillStyle = ground;
  g.fillRect(0, y, v.width, v.height - y);
  g.strokeStyle = floor;
  g.lineWidth = Math.max(1, 0.005 * Math.min(v.width, v.height));
  g.beginPath();
  g.moveTo(0, y);
  g.lineTo(v.width, y);
  // marks every half metre, so travel shows while the camera follows
  const first = Math.ceil(v.left / 0.5) * 0.5;
  for (let m = first; m < v.left + v.width / v.scale; m += 0.5) {
    const [px] = toPx(v, m, 0);
    g.moveTo(px, y);
    g.lineTo(px, y + 0.05 * v.scale);
  }
  g.stroke();
}

/** Canvas pixels [x, y] of ``count`` nodes at ``xy`` (x0, y0, x1, y1, … metres). */
export function pixels(v, xy, count) {
  const px = new Array(count);
  for (let i = 0; i < count; i++) px[i] = toPx(v, xy[2 * i], xy[2 * i + 1]);
  return px;
}

/**
 * Draw a body's springs, then its nodes: discs, or hearts and spikes where ``figure.shapes``
 * says (spikes need ``figure.anchors`` from spikeAnchors()).
 * @param {object} figure edges, radii (and shapes, anchors)
 * @param {object} paint from paints()
 * @param {Array} px node pixels from pixels()
 * @param {object} [shown] {nodes, edges}: visibility flags (drawn where non-zero); all if absent
 * @param {number} [edgeWidth] spring thickness, fraction of the smaller canvas side
 */
export function drawFigure(g, v, figure, paint, px, shown, edgeWidth = 0.005) {
  const side = Math.min(v.width, v.height);
  const visible = (i) => !shown || shown.nodes[i];
  g.lineCap = "round";
  g.lineWidth = Math.max(1, edgeWidth * side);
  figure.edges.forEach(([i, j], e) => {
    if (shown && !(shown.edges[e] && shown.nodes[i] && shown.nodes[j])) return;
    g.strokeStyle = paint.edge[e];
    g.beginPath();
    g.moveTo(...px[i]);
    g.lineTo(...px[j]);
    g.stroke();
  });
  g.lineWidth = Math.max(0.75, 0.4 * edgeWidth * side);
  figure.radii.forEach((r, i) => {
    if (!visible(i)) return;
    const radius = Math.max(2, r * v.scale);
    const shape = figure.shapes ? figure.shapes[i] : "disc";
    if (shape === "heart") heartPath(g, px[i][0], px[i][1], radius);
    else if (shape === "spike") spikePath(g, px[i], px[figure.anchors[i]], radius);
    else {
      g.beginPath();
      g.arc(px[i][0], px[i][1], radius, 0, 2 * Math.PI);
    }
    g.fillStyle = paint.node[i];
    g.fill();
    g.strokeStyle = paint.rim[i];
    g.stroke();
  });
}

/**
 * Draw one dancer.
 * @param {CanvasRenderingContext2D} g
 * @param {object} v view from view()
 * @param {object} dancer header entry: edges, radii (and colors)
 * @param {object} paint from paints()
 * @param {Float32Array} xy pose() output
 * @param {object} [overlay] {names, forces (Float32Array 2N), forceScale, fired (node indices)}
 */
export function drawDancer(g, v, dancer, paint, xy, overlay) {
  g.fillStyle = BACKGROUND;
  g.fillRect(0, 0, v.width, v.height);
  drawFloor(g, v);
  const px = pixels(v, xy, dancer.radii.length);
  drawFigure(g, v, dancer, paint, px);
  if (overlay) drawOverlay(g, v, dancer, px, overlay);
}

function drawOverlay(g, v, dancer, px, overlay) {
  const side = Math.min(v.width, v.height);
  g.lineWidth = 2;
  g.strokeStyle = RING;
  for (const i of overlay.fired) {
    const r = Math.max(2, dancer.radii[i] * v.scale);
    g.beginPath();
    g.arc(px[i][0], px[i][1], r + Math.max(3, 0.35 * r), 0, 2 * Math.PI);
    g.stroke();
  }
  if (overlay.forces) drawForces(g, px, overlay.forces, overlay.forceScale, side);
  drawLabels(g, v, px, overlay.names, dancer.radii);
}

/**
 * Force arrows from the nodes (Fig. 2 of the paper), ``scale`` pixels per newton, clipped.
 * @param {Float32Array} forces (fx0, fy0, …) newtons
 * @param {Uint8Array} [visible] node visibility; all if absent
 */
export function drawForces(g, px, forces, scale, side, visible) {
  const longest = 0.24 * side;
  g.strokeStyle = ARROW;
  g.fillStyle = ARROW;
  g.lineWidth = Math.max(1, 0.004 * side);
  px.forEach(([x, y], i) => {
    if (visible && !visible[i]) return;
    let dx = forces[2 * i] * scale;
    let dy = -forces[2 * i + 1] * scale;
    const length = Math.hypot(dx, dy);
    if (!(length >= 1.5)) return;
    const shrink = Math.min(1, longest / length);
    dx *= shrink;
    dy *= shrink;
    arrow(g, x, y, x + dx, y + dy, 4 + 0.01 * side);
  });
}

/**
 * Node names beside their nodes, on the side away from the middle of what is shown.
 * @param {object} [options] visible (node visibility flags; all if absent), ink ({text,
 *   halo} colours), size (font size, fraction of the smaller canvas side)
 */
export function drawLabels(g, v, px, names, radii, options = {}) {
  const { visible, ink = { text: TEXT, halo: BACKGROUND }, size = 0.024 } = options;
  const side = Math.min(v.width, v.height);
  const shown = px.map((_, i) => i).filter((i) => !visible || visible[i]);
  if (!shown.length) return;
  g.font = `${Math.max(9, Math.round(size * side))}px sans-serif`;
  g.textBaseline = "middle";
  const middle = shown.reduce((sum, i) => sum + px[i][0], 0) / shown.length;
  for (const i of shown) {
    const [x, y] = px[i];
    const right = x >= middle;
    const gap = Math.max(2, radii[i] * v.scale) + 3;
    g.textAlign = right ? "left" : "right";
    g.lineWidth = 3;
    g.strokeStyle = ink.halo;
    g.strokeText(names[i], right ? x + gap : x - gap, y);
    g.fillStyle = ink.text;
    g.fillText(names[i], right ? x + gap : x - gap, y);
  }
}

function arrow(g, x0, y0, x1, y1, head) {
  const angle = Math.atan2(y1 - y0, x1 - x0);
  g.beginPath();
  g.moveTo(x0, y0);
  g.lineTo(x1, y1);
  g.stroke();
  g.beginPath();
  g.moveTo(x1, y1);
  g.lineTo(x1 - head * Math.cos(angle - 0.45), y1 - head * Math.sin(angle - 0.45));
  g.lineTo(x1 - head * Math.cos(angle + 0.45), y1 - head * Math.sin(angle + 0.45));
  g.closePath();
  g.fill();
}

/** Pixels per newton that make a typical large force (90th percentile) ``fraction`` of ``side``. */
export function forceScale(forces, side, fraction = 0.12) {
  const sizes = [];
  for (let k = 0; k < forces.length; k += 2 * 7) {
    const size = Math.hypot(forces[k], forces[k + 1]);
    if (size > 0 && Number.isFinite(size)) sizes.push(size);
  }
  if (!sizes.length) return 0;
  sizes.sort((a, b) => a - b);
  return (fraction * side) / sizes[Math.floor(0.9 * (sizes.length - 1))];
}
