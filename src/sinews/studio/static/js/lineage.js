// The lineage view: the staged dancer and its ancestors, one row per
// generation, newest first, each drawn in its rest pose. Click one to go to it.

import { cameraTrack, drawDancer, extent, paints, view } from "./draw.js";

export class Lineage {
  /**
   * @param {HTMLElement} element
   * @param {function(object)} onChoose called with an ancestor ({id, run, generation, index})
   */
  constructor(element, onChoose) {
    this.element = element;
    this.onChoose = onChoose;
  }

  clear() {
    this.element.replaceChildren();
  }

  /** Show the list from GET /api/dancers/{id}/lineage. */
  show(people) {
    this.clear();
    const rows = new Map();
    for (const person of people) {
      if (!rows.has(person.generation)) rows.set(person.generation, []);
      rows.get(person.generation).push(person);
    }
    for (const [generation, members] of rows) {
      const row = document.createElement("div");
      row.className = "lineage-row";
      const label = document.createElement("span");
      label.className = "lineage-gen";
      label.textContent = `gen ${generation}`;
      row.append(label);
      for (const person of members) row.append(this.card(person));
      this.element.append(row);
    }
  }

  card(person) {
    const button = document.createElement("button");
    button.type = "button";
    button.className = "ancestor";
    button.dataset.id = person.id;
    button.dataset.generation = person.generation;
    button.dataset.index = person.index;
    button.title = `generation ${person.generation}, dancer #${person.index}`
      + (person.parents.length ? "" : " (no parents: a fresh random dancer)");
    const canvas = document.createElement("canvas");
    canvas.width = 64;
    canvas.height = 80;
    const caption = document.createElement("span");
    caption.textContent = `#${person.index}`;
    button.append(canvas, caption);
    button.addEventListener("click", () => this.onChoose(person));
    const xy = Float32Array.from(person.pose.flat());
    const track = cameraTrack(xy, 1, 0, 1, person.radii.length, 1);
    const room = extent(xy, 1, 0, 1, person.radii.length, person.radii, track);
    drawDancer(canvas.getContext("2d"), view(canvas, room, track[0]), person, paints(person), xy);
    return button;
  }
}
