// Drawing dancers on a canvas, in the look of sinews.render's FramePainter:
// discs for nodes with a darker rim, tendons in the darkened mean colour of
// their ends, a ground line, and the debug overlay (labels, force arrows,
// rings on nodes whose responder fires).

const BACKGROUND = "rgb(250,248,243)";
const GROUND = "rgb(232,228,219)";
const FLOOR = "rgb(120,114,104)";
const TEXT = "rgb(40,40,40)";
const ARROW = "rgb(214,39,40)";
const RING = "rgb(255,170,0)";

const rgb = (c, f = 1) => `rgb(${Math.round(c[0] * f)},${Math.round(c[1] * f)},${Math.round(c[2] * f)})`;

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

function drawFloor(g, v) {
  const [, y] = toPx(v, 0, 0);
  g.fillStyle = GROUND;
  g.fillRect(0, y, v.width, v.height - y);
  g.strokeStyle = FLOOR;
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
  const side = Math.min(v.width, v.height);
  const px = dancer.radii.map((_, i) => toPx(v, xy[2 * i], xy[2 * i + 1]));
  g.lineCap = "round";
  g.lineWidth = Math.max(1, 0.005 * side);
  dancer.edges.forEach(([i, j], e) => {
    g.strokeStyle = paint.edge[e];
    g.beginPath();
    g.moveTo(...px[i]);
    g.lineTo(...px[j]);
    g.stroke();
  });
  g.lineWidth = Math.max(0.75, 0.002 * side);
  dancer.radii.forEach((r, i) => {
    g.beginPath();
    g.arc(px[i][0], px[i][1], Math.max(2, r * v.scale), 0, 2 * Math.PI);
    g.fillStyle = paint.node[i];
    g.fill();
    g.strokeStyle = paint.rim[i];
    g.stroke();
  });
  if (overlay) drawOverlay(g, v, dancer, px, overlay, side);
}

function drawOverlay(g, v, dancer, px, overlay, side) {
  g.lineWidth = 2;
  g.strokeStyle = RING;
  for (const i of overlay.fired) {
    const r = Math.max(2, dancer.radii[i] * v.scale);
    g.beginPath();
    g.arc(px[i][0], px[i][1], r + Math.max(3, 0.35 * r), 0, 2 * Math.PI);
    g.stroke();
  }
  if (overlay.forces) {
    const longest = 0.24 * side;
    g.strokeStyle = ARROW;
    g.fillStyle = ARROW;
    g.lineWidth = Math.max(1, 0.004 * side);
    px.forEach(([x, y], i) => {
      let dx = overlay.forces[2 * i] * overlay.forceScale;
      let dy = -overlay.forces[2 * i + 1] * overlay.forceScale;
      const length = Math.hypot(dx, dy);
      if (!(length >= 1.5)) return;
      const shrink = Math.min(1, longest / length);
      dx *= shrink;
      dy *= shrink;
      arrow(g, x, y, x + dx, y + dy, 4 + 0.01 * side);
    });
  }
  g.font = `${Math.max(9, Math.round(0.024 * side))}px sans-serif`;
  g.textBaseline = "middle";
  const middle = px.reduce((s, p) => s + p[0], 0) / px.length;
  px.forEach(([x, y], i) => {
    const right = x >= middle;
    const gap = Math.max(2, dancer.radii[i] * v.scale) + 3;
    g.textAlign = right ? "left" : "right";
    g.lineWidth = 3;
    g.strokeStyle = BACKGROUND;
    g.strokeText(overlay.names[i], right ? x + gap : x - gap, y);
    g.fillStyle = TEXT;
    g.fillText(overlay.names[i], right ? x + gap : x - gap, y);
  });
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
