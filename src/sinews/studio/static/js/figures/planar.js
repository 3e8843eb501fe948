// Drawing planar figures from a generation pack (sinews/studio/figure_motion.py), as
// `sinews render` draws them (render/figure.py, render/figure_scene.py): the ground with
// a metre scale, a flag where the root started, the geoms, the task's marks (an X, a
// limbo post, a target), an arrow with the distance travelled.
//
// A drawer is made per pack (`planarDrawer(pack)`) and offers `view(i, w, h)` and
// `draw(ctx, i, frame, view)`; a 3D drawer (a pack whose header.drawer is not
// "planar") would offer the same two.

const SPHERE = 2, CAPSULE = 3, ELLIPSOID = 4;
const PAPER = "rgb(250,248,243)", GROUND = "rgb(232,228,219)", FLOOR = "rgb(120,114,104)";
const START = "rgb(46,139,87)", DISTANCE = "rgb(200,60,40)", CROSS = "rgb(200,40,40)";
const POST = "rgb(150,140,128)", TRACKED = "rgb(30,110,200)", TEXT = "rgb(40,40,40)";
const GROUND_SHARE = 0.2;

/** A camera: metres → canvas pixels (y up in the world, down on the canvas). */
export class View {
  constructor(width, height, scale, left, top) {
    Object.assign(this, { width, height, scale, left, top });
  }
  x(metres) { return (metres - this.left) * this.scale; }
  y(metres) { return (this.top - metres) * this.scale; }
  /** Canvas pixels → metres. */
  world(px, py) { return [px / this.scale + this.left, this.top - py / this.scale]; }
}

/** A still view showing the box [x0, x1] × [y0, y1] (metres) above a ground band. */
export function fitView(width, height, [x0, y0, x1, y1], top = 0) {
  const usable = (height - top) * (1 - GROUND_SHARE);
  const groundRow = height - GROUND_SHARE * (height - top);
  const scale = Math.min(width / (x1 - x0), (usable - 4) / (y1 - y0));
  const left = 0.5 * (x0 + x1) - (0.5 * width) / scale;
  return new View(width, height, scale, left, y0 + groundRow / scale);
}

export function planarDrawer({ header, arrays }) {
  const P = header.individuals.length, T = header.frames, s = header.scale;
  const K = header.geoms.kinds.length, S = header.sites.length;
  const { kinds, half } = header.geoms;
  const fills = header.geoms.colors.map(([r, g, b]) => `rgb(${r},${g},${b})`);
  const rims = header.geoms.colors.map(([r, g, b]) => `rgb(${r * 0.55},${g * 0.55},${b * 0.55})`);
  const centers = arrays.centers.data, ax = arrays.ax.data, az = arrays.az.data;
  const sites = arrays.sites.data, rootX = arrays.root_x.data;
  const scene = header.scene;
  const geom = (i, t, k) => 2 * ((i * T + t) * K + k);

  /** (x0, y0, x1, y1) metres: every frame of individual i, its start and the scene's marks. */
  function bounds(i) {
    let x0 = rootX[i * T] * s, x1 = x0, y0 = 0, y1 = 0.05;
    for (let t = 0; t < T; t += 2) {
      for (let k = 0; k < K; k++) {
        const g = geom(i, t, k), [h0, h1, r] = half[k];
        const rx = Math.abs(ax[g]) * s * h0 + Math.abs(az[g]) * s * h1 + r;
        const ry = Math.abs(ax[g + 1]) * s * h0 + Math.abs(az[g + 1]) * s * h1 + r;
        const cx = centers[g] * s, cy = centers[g + 1] * s;
        x0 = Math.min(x0, cx - rx); x1 = Math.max(x1, cx + rx);
        y0 = Math.min(y0, cy - ry); y1 = Math.max(y1, cy + ry);
      }
    }
    for (const [x, y] of marks()) {
      x0 = Math.min(x0, x); x1 = Math.max(x1, x); y1 = Math.max(y1, y);
    }
    const pad = 0.12 * Math.max(x1 - x0, y1 - y0, 0.1);
    return [x0 - pad, y0, x1 + pad, y1 + pad];
  }

  function marks() {
    if (!scene) return [];
    const found = [];
    if (scene.cross !== null) found.push([scene.cross, 0]);
    for (const [x, top] of scene.posts) found.push([x, 0], [x, top]);
    if (scene.target) found.push(scene.target);
    return found;
  }

  function ground(ctx, v) {
    const y = v.y(0);
    ctx.fillStyle = GROUND;
    ctx.fillRect(0, y, v.width, v.height - y);
    ctx.strokeStyle = FLOOR; ctx.lineWidth = 1.5;
    line(ctx, 0, y, v.width, y);
    const step = [0.1, 0.2, 0.25, 0.5, 1, 2, 5, 10, 1e9].find((d) => d * v.scale >= 40);
    const px = Math.max(9, 0.045 * Math.min(v.width, v.height));
    ctx.font = `${0.7 * px}px system-ui, sans-serif`;
    ctx.fillStyle = FLOOR; ctx.textAlign = "center"; ctx.textBaseline = "top"; ctx.lineWidth = 1;
    const [x0] = v.world(0, 0), [x1] = v.world(v.width, 0);
    for (let k = Math.ceil(x0 / step); k <= Math.floor(x1 / step); k++) {
      const x = v.x(k * step);
      line(ctx, x, y, x, y + 5);
      ctx.fillText(`${+(k * step).toFixed(2)}`, x, y + 6);
    }
  }

  function body(ctx, v, i, t) {
    for (let k = 0; k < K; k++) {
      const g = geom(i, t, k), [h0, h1, r] = half[k];
      const cx = centers[g] * s, cy = centers[g + 1] * s;
      const zx = az[g] * s * h1, zy = az[g + 1] * s * h1, xx = ax[g] * s * h0, xy = ax[g + 1] * s * h0;
      ctx.fillStyle = fills[k]; ctx.strokeStyle = rims[k];
      if (kinds[k] === CAPSULE || kinds[k] === SPHERE) {
        const radius = Math.max(r * v.scale, 1);
        if (kinds[k] === SPHERE || (zx === 0 && zy === 0)) {
          ctx.beginPath(); ctx.arc(v.x(cx), v.y(cy), radius, 0, 2 * Math.PI);
          ctx.fill(); ctx.lineWidth = 1; ctx.stroke();
        } else {
          ctx.lineCap = "round";
          ctx.lineWidth = 2 * radius + 2; line(ctx, v.x(cx - zx), v.y(cy - zy), v.x(cx + zx), v.y(cy + zy));
          ctx.strokeStyle = fills[k];
          ctx.lineWidth = 2 * radius; line(ctx, v.x(cx - zx), v.y(cy - zy), v.x(cx + zx), v.y(cy + zy));
          ctx.lineCap = "butt";
        }
      } else {
        ctx.beginPath();
        if (kinds[k] === ELLIPSOID) {
          for (let a = 0; a < 24; a++) {
            const c = Math.cos((a * Math.PI) / 12), n = Math.sin((a * Math.PI) / 12);
            ctx.lineTo(v.x(cx + c * xx + n * zx), v.y(cy + c * xy + n * zy));
          }
        } else {
          for (const [a, b] of [[-1, -1], [1, -1], [1, 1], [-1, 1]]) {
            ctx.lineTo(v.x(cx + a * xx + b * zx), v.y(cy + a * xy + b * zy));
          }
        }
        ctx.closePath(); ctx.fill(); ctx.lineWidth = 1; ctx.stroke();
      }
    }
  }

  function sceneBack(ctx, v, px) {
    if (!scene) return;
    ctx.strokeStyle = POST; ctx.lineWidth = Math.max(2, 0.01 * v.scale);
    for (const [x, top] of scene.posts) line(ctx, v.x(x), v.y(0), v.x(x), v.y(top));
    if (scene.cross !== null) drawCross(ctx, v.x(scene.cross), v.y(0), 0.6 * px);
  }

  function sceneFront(ctx, v, i, t, px) {
    if (!scene) return;
    const site = (name) => {
      const j = 2 * ((i * T + t) * S + header.sites.indexOf(name));
      return [sites[j] * s, sites[j + 1] * s];
    };
    const goal = scene.targetSite ? site(scene.targetSite) : scene.target;
    const radius = 0.5 * px;
    if (goal) {
      const x = v.x(goal[0]), y = v.y(goal[1]);
      ctx.strokeStyle = CROSS; ctx.lineWidth = 2;
      ctx.beginPath(); ctx.arc(x, y, radius, 0, 2 * Math.PI); ctx.stroke();
      ctx.lineWidth = 1;
      line(ctx, x - 1.6 * radius, y, x + 1.6 * radius, y);
      line(ctx, x, y - 1.6 * radius, x, y + 1.6 * radius);
    }
    if (scene.trackedSite) {
      const [x, y] = site(scene.trackedSite);
      ctx.fillStyle = TRACKED;
      ctx.beginPath(); ctx.arc(v.x(x), v.y(y), 0.45 * radius, 0, 2 * Math.PI); ctx.fill();
    }
  }

  function markers(ctx, v, i, t, px) {
    const ground = v.y(0), start = v.x(rootX[i * T] * s), now = v.x(rootX[i * T + t] * s);
    const below = Math.min(ground + 0.45 * GROUND_SHARE * v.height, v.height - 1.2 * px);
    ctx.strokeStyle = START; ctx.fillStyle = START; ctx.lineWidth = 2;
    const flag = ground - 0.12 * v.height;
    line(ctx, start, ground, start, flag);
    ctx.beginPath(); ctx.moveTo(start, flag); ctx.lineTo(start + 9, flag + 3.5); ctx.lineTo(start, flag + 7); ctx.fill();
    ctx.strokeStyle = DISTANCE; ctx.fillStyle = DISTANCE;
    if (Math.abs(now - start) >= 2) {
      line(ctx, start, below, now, below);
      const d = Math.sign(now - start);
      ctx.beginPath(); ctx.moveTo(now, below); ctx.lineTo(now - 6 * d, below - 3.5); ctx.lineTo(now - 6 * d, below + 3.5); ctx.fill();
    }
    const metres = Math.abs(rootX[i * T + t] - rootX[i * T]) * s;
    ctx.font = `${0.9 * px}px system-ui, sans-serif`; ctx.textAlign = "center"; ctx.textBaseline = "top";
    ctx.fillText(`${metres.toFixed(2)} m`, Math.min(Math.max(0.5 * (start + now), 3 * px), v.width - 3 * px), below + 3);
  }

  return {
    kind: "planar",
    individuals: P,
    frames: T,
    fps: header.fps,
    /** The still camera of individual i on a width × height canvas (below a band of `top` px). */
    view(i, width, height, top = 0) {
      return fitView(width, height, bounds(i), top);
    },
    /** Draw frame t of individual i. */
    draw(ctx, i, t, v) {
      const px = Math.max(9, 0.045 * Math.min(v.width, v.height));
      ctx.fillStyle = PAPER;
      ctx.fillRect(0, 0, v.width, v.height);
      ground(ctx, v);
      sceneBack(ctx, v, px);
      body(ctx, v, i, t);
      sceneFront(ctx, v, i, t, px);
      markers(ctx, v, i, t, px);
      if (v.width < 400) return; // a grid cell: the page's clock says the time
      ctx.fillStyle = TEXT; ctx.textAlign = "right"; ctx.textBaseline = "top";
      ctx.font = `${px}px system-ui, sans-serif`;
      ctx.fillText(`${(t / header.fps).toFixed(1)} s`, v.width - 0.4 * px, v.height - 1.4 * px);
    },
  };
}

function line(ctx, x0, y0, x1, y1) {
  ctx.beginPath(); ctx.moveTo(x0, y0); ctx.lineTo(x1, y1); ctx.stroke();
}

/** The X on the floor at (x, y) pixels, half-width `half`, as render/figure_scene.py draws it. */
export function drawCross(ctx, x, y, half) {
  ctx.strokeStyle = CROSS; ctx.lineWidth = 3;
  const cy = y + 0.5 * half;
  for (const sign of [-1, 1]) line(ctx, x - half, cy - sign * 0.5 * half, x + half, cy + sign * 0.5 * half);
}
