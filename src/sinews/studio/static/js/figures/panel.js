// The staged figure's controller: a spring net drawn as render/figure_panel.py draws it
// (masses as dots moving on the net's axis, springs as arcs, a driving mass in the colour
// of the part its joint moves), or a GP program as an indented S-expression.

const HIDDEN = "rgb(150,150,150)", SPRING = "rgb(170,165,155)";

/**
 * Draw individual i's net at frame t in the band [0, width] × [0, height] of ctx.
 * @param {object} net {masses, springs, outputs, labels} from the pack header
 * @param {Float32Array} positions (P, T, n) the nets' motion
 */
export function drawNet(ctx, net, positions, i, t, frames, jointColors, width, height) {
  const n = net.masses.length, base = i * frames * n;
  ctx.fillStyle = "rgb(240,238,233)";
  ctx.fillRect(0, 0, width, height);
  ctx.strokeStyle = "rgb(200,198,194)"; ctx.lineWidth = 1;
  ctx.beginPath(); ctx.moveTo(0, height - 0.5); ctx.lineTo(width, height - 0.5); ctx.stroke();
  let lo = Infinity, hi = -Infinity;
  for (let k = base; k < base + frames * n; k++) {
    if (Number.isFinite(positions[k])) { lo = Math.min(lo, positions[k]); hi = Math.max(hi, positions[k]); }
  }
  if (!Number.isFinite(lo)) { lo = -1; hi = 1; }
  const pad = Math.max(0.08 * (hi - lo), 0.5 * Math.max(0, 0.3 - (hi - lo)));
  lo -= pad; hi += pad;
  const textPx = Math.max(8, 0.16 * height), margin = 0.06 * width, axisY = 0.55 * height;
  ctx.fillStyle = "rgb(40,40,40)"; ctx.font = `${textPx}px system-ui, sans-serif`;
  ctx.textAlign = "left"; ctx.textBaseline = "top";
  ctx.fillText("spring net", 4, 3);
  const x = (j) => margin + ((positions[base + t * n + j] - lo) / (hi - lo)) * (width - 2 * margin);
  ctx.strokeStyle = "rgb(175,174,170)";
  ctx.beginPath(); ctx.moveTo(margin, axisY); ctx.lineTo(width - margin, axisY); ctx.stroke();
  ctx.strokeStyle = SPRING;
  for (let a = 0; a < n; a++) {
    for (let b = a + 1; b < n; b++) {
      const k = net.springs[a][b];
      if (k <= 0) continue;
      const x0 = x(a), x1 = x(b), rise = Math.min(0.4 * height, 0.5 * Math.abs(x1 - x0));
      if (rise < 0.5) continue;
      ctx.lineWidth = 0.5 + (2.5 * k) / 100;
      ctx.beginPath();
      ctx.ellipse(0.5 * (x0 + x1), axisY, 0.5 * Math.abs(x1 - x0), rise, 0, Math.PI, 2 * Math.PI);
      ctx.stroke();
    }
  }
  const drives = new Map();
  net.outputs.forEach((mass, joint) => drives.set(mass, [...(drives.get(mass) || []), joint]));
  const order = [...net.masses.keys()].sort((a, b) => net.masses[b] - net.masses[a]);
  for (const j of order) {
    const radius = Math.max(2.5, 0.13 * height * Math.cbrt(net.masses[j] / 10));
    const joints = drives.get(j) || [];
    const [r, g, b] = joints.length ? jointColors[joints[0]] : [150, 150, 150];
    ctx.fillStyle = joints.length ? `rgb(${r},${g},${b})` : HIDDEN;
    ctx.strokeStyle = `rgb(${r * 0.55},${g * 0.55},${b * 0.55})`; ctx.lineWidth = 1;
    ctx.beginPath(); ctx.arc(x(j), axisY, radius, 0, 2 * Math.PI); ctx.fill(); ctx.stroke();
    if (joints.length) {
      ctx.fillStyle = `rgb(${r * 0.6},${g * 0.6},${b * 0.6})`;
      ctx.font = `${0.85 * textPx}px system-ui, sans-serif`; ctx.textAlign = "center";
      ctx.fillText(joints.map((k) => net.labels[k]).join(","), x(j), axisY + radius + 1);
    }
  }
}

/** A GP program (one S-expression per joint, `(list …)`) indented so no line runs past `width`. */
export function prettyProgram(text, width = 72) {
  const tokens = text.match(/\(|\)|[^\s()]+/g) || [];
  let at = 0;
  const parse = () => {
    const token = tokens[at++];
    if (token !== "(") return token;
    const items = [];
    while (at < tokens.length && tokens[at] !== ")") items.push(parse());
    at++;
    return items;
  };
  const flat = (node) => (Array.isArray(node) ? `(${node.map(flat).join(" ")})` : node);
  const show = (node, indent) => {
    const one = flat(node);
    if (!Array.isArray(node) || indent.length + one.length <= width) return indent + one;
    const [head, ...rest] = node;
    const inner = indent + "  ";
    return `${indent}(${flat(head)}\n${rest.map((n) => show(n, inner)).join("\n")})`;
  };
  const lines = [];
  while (at < tokens.length) lines.push(show(parse(), ""));
  return lines.join("\n");
}
