// The fitness plot: best and mean fitness per generation, drawn on a canvas.

const BEST = "rgb(212,86,42)", MEAN = "rgb(42,123,212)", AXIS = "rgb(122,116,106)";

/**
 * Draw a run's history on canvas.
 * @param {HTMLCanvasElement} canvas
 * @param {{generation: number, best: ?number, mean: ?number}[]} history
 * @param {string} label what fitness measures
 * @param {?number} shown the generation on screen (a marker), or null
 */
export function drawPlot(canvas, history, label, shown) {
  const ctx = canvas.getContext("2d"), w = canvas.width, h = canvas.height;
  ctx.fillStyle = "white";
  ctx.fillRect(0, 0, w, h);
  const left = 56, right = 12, top = 22, bottom = 28;
  const values = history.flatMap((g) => [g.best, g.mean]).filter((v) => v !== null);
  ctx.font = "12px system-ui, sans-serif";
  ctx.fillStyle = AXIS;
  ctx.textBaseline = "top";
  ctx.textAlign = "left";
  ctx.fillText(label, left, 4);
  if (!values.length) {
    ctx.textAlign = "center";
    ctx.fillText("no scored generation yet", w / 2, h / 2);
    return;
  }
  let lo = Math.min(...values), hi = Math.max(...values);
  if (hi - lo < 1e-9) { lo -= 0.5; hi += 0.5; }
  const last = Math.max(1, history[history.length - 1].generation);
  const x = (g) => left + (g / last) * (w - left - right);
  const y = (v) => top + (1 - (v - lo) / (hi - lo)) * (h - top - bottom);
  ctx.strokeStyle = "rgb(230,226,218)";
  ctx.lineWidth = 1;
  ctx.textAlign = "right";
  ctx.textBaseline = "middle";
  for (let k = 0; k <= 4; k++) {
    const v = lo + ((hi - lo) * k) / 4;
    ctx.beginPath(); ctx.moveTo(left, y(v)); ctx.lineTo(w - right, y(v)); ctx.stroke();
    ctx.fillText(v.toPrecision(3), left - 4, y(v));
  }
  ctx.textAlign = "center";
  ctx.textBaseline = "top";
  const step = Math.max(1, Math.ceil(last / 10));
  for (let g = 0; g <= last; g += step) ctx.fillText(String(g), x(g), h - bottom + 4);
  if (shown !== null && shown <= last) {
    ctx.strokeStyle = "rgb(224,161,0)";
    ctx.beginPath(); ctx.moveTo(x(shown), top); ctx.lineTo(x(shown), h - bottom); ctx.stroke();
  }
  for (const [key, color] of [["mean", MEAN], ["best", BEST]]) {
    ctx.strokeStyle = color;
    ctx.fillStyle = color;
    ctx.lineWidth = 2;
    ctx.beginPath();
    for (const g of history) if (g[key] !== null) ctx.lineTo(x(g.generation), y(g[key]));
    ctx.stroke();
    for (const g of history) {
      if (g[key] === null) continue;
      ctx.beginPath(); ctx.arc(x(g.generation), y(g[key]), 2.5, 0, 2 * Math.PI); ctx.fill();
    }
  }
  ctx.textAlign = "right";
  ctx.fillStyle = BEST; ctx.fillText("best", w - right - 44, 4);
  ctx.fillStyle = MEAN; ctx.fillText("mean", w - right, 4);
}
