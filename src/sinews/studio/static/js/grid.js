// The breeding grid: every dancer of a generation, dancing at the clock's frame.
// Click a dancer to pick it (again to unpick); its "stage" button shows it large.

import { cameraTrack, drawDancer, extent, paints, pose, view } from "./draw.js";

export class Grid {
  /**
   * @param {HTMLElement} element the grid container
   * @param {{onPicks: function(Set<number>), onStage: function(object)}} hooks
   */
  constructor(element, hooks) {
    this.element = element;
    this.hooks = hooks;
    this.generation = null;
    this.cells = [];
    this.picks = new Set();
    this.staged = null;
  }

  /** Show a decoded generation pack. */
  show(generation) {
    this.generation = generation;
    this.picks = new Set();
    const { header, arrays } = generation;
    const [count, frames, nodes] = arrays.positions.shape;
    const data = arrays.positions.data;
    this.element.replaceChildren();
    document.documentElement.style.setProperty("--columns", count > 16 ? 5 : 4);
    this.cells = header.dancers.map((dancer, index) => {
      const offset = index * frames * nodes * 2;
      const cell = this.makeCell(dancer, index);
      const track = cameraTrack(data, header.scale, offset, frames, nodes, header.fps);
      return {
        dancer,
        index,
        offset,
        track,
        room: extent(data, header.scale, offset, frames, nodes, dancer.radii, track),
        element: cell,
        canvas: cell.querySelector("canvas"),
        paint: paints(dancer),
      };
    });
    // One scale for all, as on a contact sheet, so a big dancer looks big: room for
    // three dancers in four (the biggest may reach past the edges now and then).
    const upper = (values) => values.sort((a, b) => a - b)[Math.floor(0.75 * (values.length - 1))];
    const room = {
      top: upper(this.cells.map((c) => c.room.top)),
      half: upper(this.cells.map((c) => c.room.half)),
    };
    this.size = { frames, nodes, room };
    this.resize();
    this.hooks.onPicks(this.picks);
  }

  makeCell(dancer, index) {
    const cell = document.createElement("div");
    cell.className = "cell";
    cell.dataset.index = index;
    cell.dataset.id = dancer.id;
    cell.dataset.parents = dancer.parents.join(" ");
    cell.classList.toggle("failed", dancer.failed);
    cell.classList.toggle("was-picked", dancer.picked);
    cell.title = dancer.failed ? "this dancer blew up" : "click to pick";
    const canvas = document.createElement("canvas");
    canvas.setAttribute("aria-label", `dancer ${index}`);
    const label = document.createElement("span");
    label.className = "label";
    label.textContent = `#${index}${dancer.picked ? " ✓" : ""}`;
    const stage = document.createElement("button");
    stage.type = "button";
    stage.className = "to-stage";
    stage.textContent = "stage";
    stage.title = "show this dancer on the stage (and its lineage)";
    stage.addEventListener("click", (event) => {
      event.stopPropagation();
      this.hooks.onStage(dancer);
    });
    cell.addEventListener("click", () => this.toggle(index));
    cell.append(canvas, label, stage);
    this.element.append(cell);
    return cell;
  }

  toggle(index) {
    if (this.picks.has(index)) this.picks.delete(index);
    else this.picks.add(index);
    this.cells[index].element.classList.toggle("picked", this.picks.has(index));
    this.hooks.onPicks(this.picks);
  }

  clearPicks() {
    for (const cell of this.cells) cell.element.classList.remove("picked");
    this.picks = new Set();
    this.hooks.onPicks(this.picks);
  }

  /** Mark the dancer shown on the stage. */
  setStaged(id) {
    this.staged = id;
    for (const cell of this.cells) cell.element.classList.toggle("staged", cell.dancer.id === id);
  }

  resize() {
    const ratio = window.devicePixelRatio || 1;
    for (const cell of this.cells) {
      const box = cell.canvas.getBoundingClientRect();
      cell.canvas.width = Math.max(1, Math.round(box.width * ratio));
      cell.canvas.height = Math.max(1, Math.round(box.height * ratio));
    }
  }

  /** Draw every dancer at ``frame``. */
  draw(frame) {
    if (!this.generation) return;
    const { header, arrays } = this.generation;
    const { frames, nodes, room } = this.size;
    const t = Math.min(Math.max(frame, 0), frames - 1);
    for (const cell of this.cells) {
      const g = cell.canvas.getContext("2d");
      const v = view(cell.canvas, room, cell.track[t]);
      const xy = pose(arrays.positions.data, header.scale, cell.offset + t * nodes * 2, nodes);
      drawDancer(g, v, cell.dancer, cell.paint, xy);
    }
  }
}
