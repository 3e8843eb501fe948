// Scene frames as the server sends them (see sinews.studio.scene_live), and what to draw
// between them: the page draws at its own 60 fps, one frame interval behind the latest
// frame, blending from the one before it, so a frame that arrives late or early does not
// make the motion stutter.

const HEAD_FLOATS = 8;

/**
 * One binary frame.
 * @param {ArrayBuffer} buffer
 * @param {number} nodes N of the scene's header
 * @param {number} edges E of the scene's header
 */
export function decodeFrame(buffer, nodes, edges) {
  const head = new Float32Array(buffer, 0, HEAD_FLOATS);
  let offset = 4 * HEAD_FLOATS;
  const take = (Kind, count, size) => {
    const array = new Kind(buffer, offset, count);
    offset += count * size;
    return array;
  };
  const positions = take(Float32Array, 2 * nodes, 4);
  const flags = head[7];
  const forces = flags & 1 ? take(Float32Array, 2 * nodes, 4) : null;
  const nodeVisible = take(Uint8Array, nodes, 1);
  const edgeVisible = take(Uint8Array, edges, 1);
  if (offset !== buffer.byteLength) throw new Error(`a scene frame of ${buffer.byteLength} bytes`);
  return {
    step: head[0],
    score: head[1],
    camera: [head[2], head[3]],
    seq: head[4],
    grabbed: head[5] < 0 ? null : head[5],
    gauge: head[6],
    paused: Boolean(flags & 2),
    positions,
    forces,
    nodeVisible,
    edgeVisible,
    arrived: performance.now(),
  };
}

/** The latest two frames, and the blend of them to draw at a given moment. */
export class FrameBuffer {
  /** @param {number} fps the scene's frame rate */
  constructor(fps) {
    this.interval = 1000 / fps;
    this.previous = null;
    this.latest = null;
  }

  push(frame) {
    this.previous = this.latest;
    this.latest = frame;
  }

  /**
   * What to draw at ``now`` (ms): positions and camera between the previous and the latest
   * frame, reaching the latest one a frame interval after it arrived. Nodes that appeared
   * or vanished in between are not blended (they jumped).
   */
  at(now) {
    const [a, b] = [this.previous, this.latest];
    if (!b) return null;
    const t = a ? Math.min(1, Math.max(0, (now - b.arrived) / this.interval)) : 1;
    if (t === 1) return { ...b, xy: b.positions };
    const xy = new Float32Array(b.positions.length);
    for (let i = 0; i < b.nodeVisible.length; i++) {
      const blend = a.nodeVisible[i] && b.nodeVisible[i] ? t : 1;
      for (const k of [2 * i, 2 * i + 1]) xy[k] = a.positions[k] + blend * (b.positions[k] - a.positions[k]);
    }
    const camera = [0, 1].map((k) => a.camera[k] + t * (b.camera[k] - a.camera[k]));
    return { ...b, xy, camera };
  }
}
