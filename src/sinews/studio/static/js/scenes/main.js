// The scene pages: the seed-000 prototypes played live. The server simulates the scene
// and streams frames (SceneLink); this page sends the keys, the mouse and drawings, and
// draws the frames at its own 60 fps (ScenePainter), one tab per scene (#scribbles, …).
// ?seed=N in the address plays that seed (as `sinews scene --seed N`).

import { SceneInput } from "./input.js";
import { SceneLink } from "./link.js";
import { ScenePainter } from "./painter.js";

const $ = (id) => document.getElementById(id);

const SCENES = {
  scribbles: {
    hint: `Draw a curve with the mouse: on release it comes alive with tendons of its own and
      twitches, coils or crawls (head first: the big dot). Up to four live at once. Click or
      drag a scribble to select it; Regenerate tendons gives it a new personality.`,
    gauge: () => "",
  },
  "falling-for-you": {
    hint: `The camera follows your doll (the orange mark). Hold ← or → to push it toward
      someone, or hard away from a held hand to break up. Left alone, the dolls fall, long for
      each other, link hands, and balloons lift the couples. You can also drag any node.`,
    gauge: (value) => `strongest held hand: ${Math.round(100 * value)} % of breaking`,
  },
  kittens: {
    hint: `Drag any node of a kitten and fling it off the screen. Which node you grab matters:
      a tail stretches, a back hauls the whole cat. Kittens come faster and faster.`,
    gauge: (value) => `a kitten every ${value.toFixed(2)} s`,
  },
};

const sceneFromHash = () => (location.hash.slice(1) in SCENES ? location.hash.slice(1) : "scribbles");

class ScenePage {
  constructor() {
    const canvas = $("scene");
    this.painter = new ScenePainter(canvas);
    this.link = new SceneLink({
      scene: (header) => this.showScene(header),
      events: (message) => this.showEvents(message),
      error: (text) => this.message(text, true),
      closed: () => this.message("The link to the server closed; press Restart.", true),
    });
    this.input = new SceneInput(canvas, this.painter, {
      draws: () => this.name === "scribbles",
      visible: () => this.shown && this.shown.nodeVisible,
      grabbed: (node) => this.selectAt(node),
      stroke: (points) => this.link.input("stroke", { points }),
    });
    this.name = null;
    this.scribbles = {}; // live scribbles: id -> node indices
    this.selected = null; // id of the selected scribble
    this.events = []; // everything that happened, for whoever wants to know
    this.sentInput = "";
    this.shown = null;
    this.statsShown = 0;
    $("overlay").addEventListener("change", () => this.link.send({ op: "overlay", on: $("overlay").checked }));
    $("pause").addEventListener("click", () => this.pause(!this.paused));
    $("restart").addEventListener("click", () => this.open(this.name));
    $("reroll").addEventListener("click", () => this.link.send({ op: "reroll", scribble: this.selected }));
    addEventListener("hashchange", () => this.open(sceneFromHash()));
    addEventListener("resize", () => this.painter.header && this.painter.resize());
  }

  /** Play scene ``name`` from the address's seed, or a random one. */
  async open(name) {
    this.name = name;
    for (const tab of document.querySelectorAll("#tabs a")) {
      tab.setAttribute("aria-current", String(tab.hash === `#${name}`));
    }
    $("hint").textContent = SCENES[name].hint.replace(/\s+/g, " ");
    $("reroll").hidden = name !== "scribbles";
    this.scribbles = {};
    this.select(null);
    this.events = [];
    this.shown = null;
    this.paused = false;
    $("pause").textContent = "Pause";
    this.message("");
    const given = new URLSearchParams(location.search).get("seed");
    const seed = given !== null && /^\d+$/.test(given) ? Number(given) : Math.floor(Math.random() * 2 ** 31);
    try {
      await this.link.start(name, seed);
    } catch (error) {
      this.message(error.message, true);
    }
  }

  showScene(header) {
    this.header = header;
    this.painter.setScene(header);
    if ($("overlay").checked) this.link.send({ op: "overlay", on: true });
    document.title = `sinews · ${$("tabs").querySelector(`[href="#${header.scene}"]`).textContent}`;
  }

  showEvents(message) {
    this.scribbles = message.scribbles;
    for (const [kind, ids] of message.events) {
      this.events.push({ step: message.step, kind, ids });
      if (kind === "scribble") this.select(ids[0]);
    }
    if (!(this.selected in this.scribbles)) this.select(null);
  }

  /** Select the scribble that node ``node`` belongs to (pressing it). */
  selectAt(node) {
    const found = Object.entries(this.scribbles).find(([, nodes]) => nodes.includes(node));
    if (found) this.select(Number(found[0]));
  }

  select(id) {
    this.selected = id;
    $("reroll").disabled = id === null;
  }

  pause(on) {
    this.paused = on;
    $("pause").textContent = on ? "Play" : "Pause";
    this.link.send({ op: "pause", on });
  }

  message(text, error = false) {
    const box = $("message");
    box.textContent = text;
    box.hidden = !text;
    box.classList.toggle("error", error);
  }

  /** Every animation frame: send the input if it changed, draw, show the numbers. */
  tick(now) {
    if (!this.link.frames || !this.link.frames.latest) return;
    const input = this.input.state();
    const text = JSON.stringify(input);
    if (text !== this.sentInput) {
      this.link.input("input", input);
      this.sentInput = text;
    }
    const shown = (this.shown = this.link.frames.at(now));
    const focus = this.header.focus;
    const selected = this.scribbles[this.selected];
    const pull = this.input.held;
    const stroke = this.input.stroke;
    this.painter.draw(shown, { overlay: $("overlay").checked, focus, selected, pull, stroke });
    document.body.dataset.step = shown.step;
    $("score").textContent = `${this.header.scoreName}: ${shown.score}`;
    $("gauge").textContent = Number.isNaN(shown.gauge) ? "" : SCENES[this.name].gauge(shown.gauge);
    if (now - this.statsShown > 500) this.showStats(now);
  }

  showStats(now) {
    this.statsShown = now;
    const s = this.link.summary();
    const ms = (value) => (Number.isFinite(value) ? value.toFixed(value < 10 ? 2 : 0) : "–");
    $("stats").textContent =
      `server: step ${ms(s.step)} ms (max ${ms(s.stepMax)}) + pack ${ms(s.pack)} ms` +
      ` · ping ${ms(s.ping)} ms · input→frame ${ms(s.input)} ms · ` +
      (this.shown.paused ? "paused" : `${ms(s.fps)} frames/s`);
  }
}

const page = new ScenePage();
window.scenes = page;
page.open(sceneFromHash());
const tick = (now) => {
  page.tick(now);
  requestAnimationFrame(tick);
};
requestAnimationFrame(tick);
