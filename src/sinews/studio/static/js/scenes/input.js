// The player's hands on a scene page: the arrow keys (a push, −1…1), the mouse pressing
// and dragging a node, and — in Scribbles — drawing: a press away from every scribble
// draws a curve, sent as a stroke on release.

const GRAB_PIXELS = 14;
const STEP_PIXELS = 4;
const MAX_POINTS = 2000;
const METRES = 99; // the server takes points within ±100 m

/** Metres, rounded to 0.1 mm and within what the server takes. */
const metres = (point) => point.map((m) => Math.min(METRES, Math.max(-METRES, Math.round(m * 1e4) / 1e4)));

export class SceneInput {
  /**
   * @param {HTMLCanvasElement} canvas
   * @param {import("./painter.js").ScenePainter} painter
   * @param {{draws: function(): boolean, visible: function(): ?Uint8Array,
   *   grabbed: function(number), stroke: function(Array)}} hooks whether a press away from
   *   nodes draws; visibility of the nodes as last drawn (null: nothing drawn yet); a node
   *   was pressed; a finished stroke (metres)
   */
  constructor(canvas, painter, hooks) {
    this.canvas = canvas;
    this.painter = painter;
    this.hooks = hooks;
    this.keys = { ArrowLeft: false, ArrowRight: false };
    this.held = null; // pixels of the pointer while it holds a node
    this.stroke = null; // pixels of the curve being drawn
    this.pressedOnce = false; // a press shorter than a frame still grabs, where it was
    this.pressedAt = null;
    canvas.addEventListener("pointerdown", (event) => this.press(event));
    canvas.addEventListener("pointermove", (event) => this.move(event));
    canvas.addEventListener("pointerup", () => this.release());
    canvas.addEventListener("pointercancel", () => this.release());
    addEventListener("keydown", (event) => this.key(event, true));
    addEventListener("keyup", (event) => this.key(event, false));
    addEventListener("blur", () => {
      this.keys.ArrowLeft = this.keys.ArrowRight = false;
    });
  }

  key(event, down) {
    if (!(event.key in this.keys)) return;
    event.preventDefault();
    this.keys[event.key] = down;
  }

  /** Pointer position in canvas pixels. */
  pixels(event) {
    const box = this.canvas.getBoundingClientRect();
    return [
      ((event.clientX - box.left) * this.canvas.width) / box.width,
      ((event.clientY - box.top) * this.canvas.height) / box.height,
    ];
  }

  press(event) {
    const visible = this.hooks.visible();
    if (!visible || event.button !== 0) return;
    event.preventDefault();
    this.canvas.setPointerCapture(event.pointerId);
    const at = this.pixels(event);
    const node = this.painter.nodeAt(at, visible, GRAB_PIXELS);
    if (node === null && this.hooks.draws()) {
      this.stroke = [at];
      return;
    }
    if (node !== null) this.hooks.grabbed(node);
    this.held = this.pressedAt = at;
    this.pressedOnce = true;
    this.canvas.classList.add("dragging");
  }

  move(event) {
    const at = this.pixels(event);
    if (this.held) this.held = at;
    const last = this.stroke && this.stroke[this.stroke.length - 1];
    if (last && this.stroke.length < MAX_POINTS && Math.hypot(at[0] - last[0], at[1] - last[1]) >= STEP_PIXELS) {
      this.stroke.push(at);
    }
  }

  release() {
    this.held = null;
    this.canvas.classList.remove("dragging");
    const stroke = this.stroke;
    this.stroke = null;
    if (stroke && stroke.length >= 2) this.hooks.stroke(stroke.map((p) => metres(this.painter.toWorld(p))));
  }

  /** The keys and mouse now, as the server takes them: {push, pointer (metres) | null, pressed}. */
  state() {
    const at = this.held ?? (this.pressedOnce ? this.pressedAt : null);
    this.pressedOnce = false;
    return {
      push: (this.keys.ArrowRight ? 1 : 0) - (this.keys.ArrowLeft ? 1 : 0),
      pointer: at ? metres(this.painter.toWorld(at)) : null,
      pressed: at !== null,
    };
  }
}
