// Node shapes besides discs, as sinews.render's painter draws them: hearts (balloons in
// Falling for You) and spikes (kitten ears) pointing away from the node's first spring.

/** The classic heart curve, 48 points, x and y (canvas, down) in [-1, 1], centred on its box. */
const HEART = (() => {
  const points = [];
  for (let k = 0; k < 48; k++) {
    const t = (2 * Math.PI * k) / 48;
    const x = 16 * Math.sin(t) ** 3;
    const y = 13 * Math.cos(t) - 5 * Math.cos(2 * t) - 2 * Math.cos(3 * t) - Math.cos(4 * t);
    points.push([x, y]);
  }
  const ys = points.map(([, y]) => y);
  const middle = 0.5 * (Math.max(...ys) + Math.min(...ys));
  return points.map(([x, y]) => [x / 16, -(y - middle) / 16]);
})();

/** Each node's anchor for a spike: the other end of its first spring (itself if it has none). */
export function spikeAnchors(edges, count) {
  const anchors = Array.from({ length: count }, (_, i) => i);
  const seen = new Uint8Array(count);
  for (const [i, j] of edges) {
    if (!seen[i]) [anchors[i], seen[i]] = [j, 1];
    if (!seen[j]) [anchors[j], seen[j]] = [i, 1];
  }
  return anchors;
}

/** Path of a heart of radius ``r`` pixels on (x, y). */
export function heartPath(g, x, y, r) {
  g.beginPath();
  HEART.forEach(([hx, hy], k) => (k ? g.lineTo : g.moveTo).call(g, x + r * hx, y + r * hy));
  g.closePath();
}

/** Path of a triangle on ``point`` pointing away from ``anchor`` (up if they coincide). */
export function spikePath(g, [x, y], [ax, ay], r) {
  const length = Math.hypot(x - ax, y - ay);
  const [ux, uy] = length > 1e-9 ? [(x - ax) / length, (y - ay) / length] : [0, -1];
  const [bx, by] = [x - 0.6 * r * ux, y - 0.6 * r * uy];
  const half = 1.1 * r;
  g.beginPath();
  g.moveTo(x + 1.6 * r * ux, y + 1.6 * r * uy);
  g.lineTo(bx - half * uy, by + half * ux);
  g.lineTo(bx + half * uy, by - half * ux);
  g.closePath();
}
