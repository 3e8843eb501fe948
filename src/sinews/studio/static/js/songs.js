// Songs: choose a demo or an uploaded song, upload your own, correct the tempo.
// Another song means dancing on in a new run (a branch); the tempo is the run's.

import { getJSON, postFile, postJSON, StudioError } from "./api.js";

export class Songs {
  /**
   * @param {object} elements {select, upload, tempo, half, double, auto}
   * @param {object} app {run, maxUpload, busy(label, work), openRun(run), message(text)}
   */
  constructor(elements, app) {
    this.elements = elements;
    this.app = app;
    elements.select.addEventListener("change", () => this.choose(elements.select.value));
    elements.upload.addEventListener("change", () => this.upload(elements.upload.files[0]));
    elements.half.addEventListener("click", () => this.retempo(0.5));
    elements.double.addEventListener("click", () => this.retempo(2));
    elements.auto.addEventListener("click", () => this.retempo(null));
  }

  /** Fill the song list (and select the run's song). */
  async refresh(songs) {
    const list = songs || (await getJSON("/api/songs"));
    const { select } = this.elements;
    select.replaceChildren(
      ...list.map((song) => {
        const option = document.createElement("option");
        option.value = song.id;
        option.textContent = song.name;
        return option;
      }),
    );
    this.showRun(this.app.run);
  }

  /** Show a run's song and tempo. */
  showRun(run) {
    if (!run) return;
    const { select, tempo } = this.elements;
    if (![...select.options].some((o) => o.value === run.song.id)) {
      const option = document.createElement("option");
      option.value = run.song.id;
      option.textContent = run.song.name;
      select.append(option);
    }
    select.value = run.song.id;
    tempo.textContent = `${run.tempo.toFixed(1)} BPM${run.bpm ? " (set)" : ""}`;
  }

  /** Dance on to another song from the generation on show. */
  async choose(songId) {
    const run = this.app.run;
    if (songId === run.song.id) return;
    await this.app.busy("Changing the song…", async () => {
      const branch = await postJSON(`/api/runs/${run.id}/song`, {
        song: songId,
        generation: this.app.generationNumber,
      });
      await this.app.openRun(branch);
      this.app.message(`Run ${branch.id}: generation ${branch.last} dances on to ${branch.song.name}.`);
    });
    this.showRun(this.app.run); // after a failure, show the song still playing
  }

  async upload(file) {
    this.elements.upload.value = "";
    if (!file) return;
    await this.app.busy(`Analysing ${file.name}…`, async () => {
      if (file.size > this.app.maxUpload) {
        throw new StudioError(`${file.name}: larger than ${Math.round(this.app.maxUpload / 2 ** 20)} MB`);
      }
      const song = await postFile("/api/songs", file);
      await this.refresh();
      await this.choose(song.id);
    });
  }

  /** Multiply the tempo by ``factor`` (null: back to the analysed tempo). */
  async retempo(factor) {
    const run = this.app.run;
    const bpm = factor === null ? null : run.tempo * factor;
    await this.app.busy("Re-analysing the beats…", async () => {
      const changed = await postJSON(`/api/runs/${run.id}/bpm`, { bpm });
      await this.app.openRun(changed, this.app.generationNumber);
    });
  }
}
