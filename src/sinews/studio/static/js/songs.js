// Songs: choose a demo or an uploaded song, upload your own, correct the tempo, nudge
// the beats. Another song means dancing on in a new run (a branch); tempo and nudge
// are the run's.

import { getJSON, postFile, postJSON, StudioError } from "./api.js";
import { TapTempo } from "./tap.js";

export const MIN_BPM = 40;
export const MAX_BPM = 240;
/** One nudge moves the beats this fraction of a beat; at most MAX_SHIFT either way. */
export const SHIFT_STEP = 0.125;
export const MAX_SHIFT = 0.5;

export class Songs {
  /**
   * @param {object} elements {select, upload, tempo, half, double, auto, form, bpm, tap,
   *   shift, earlier, later}
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
    elements.form.addEventListener("submit", (event) => {
      event.preventDefault();
      this.setTempo(Number(elements.bpm.value));
    });
    this.tapper = new TapTempo(
      (bpm) => this.setTempo(Math.round(bpm * 10) / 10),
      (taps, bpm) => this.showTaps(taps, bpm),
    );
    elements.tap.addEventListener("click", () => this.tapper.tap());
    elements.earlier.addEventListener("click", () => this.nudge(-SHIFT_STEP));
    elements.later.addEventListener("click", () => this.nudge(SHIFT_STEP));
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
    if (document.activeElement !== this.elements.bpm) this.elements.bpm.value = run.tempo.toFixed(1);
    const eighths = Math.round(run.beatShift / SHIFT_STEP);
    this.elements.shift.textContent =
      eighths === 0 ? "beats ±0" : `beats ${eighths > 0 ? "+" : "−"}${Math.abs(eighths)}/8`;
    this.elements.earlier.disabled = run.beatShift <= -MAX_SHIFT;
    this.elements.later.disabled = run.beatShift >= MAX_SHIFT;
  }

  /** Move the run's beats by ``step`` of a beat (later if positive). */
  async nudge(step) {
    const run = this.app.run;
    const shift = Math.max(-MAX_SHIFT, Math.min(MAX_SHIFT, run.beatShift + step));
    await this.app.busy("Moving the beats…", async () => {
      const changed = await postJSON(`/api/runs/${run.id}/shift`, { shift: shift || null });
      await this.app.openRun(changed, this.app.generationNumber);
    });
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
    await this.setTempo(factor === null ? null : this.app.run.tempo * factor, false);
  }

  /** Show the tap count and the tempo tapped so far on the tap button. */
  showTaps(taps, bpm) {
    const { tap, bpm: field } = this.elements;
    tap.textContent = taps === 0 ? "Tap" : `Tap ${taps}${bpm ? ` · ${bpm.toFixed(1)}` : ""}`;
    if (bpm) field.value = bpm.toFixed(1);
  }

  /** Dance at ``bpm`` (null: the analysed tempo); typed and tapped ones must be 40–240. */
  async setTempo(bpm, checked = true) {
    const run = this.app.run;
    if (checked && !(Number.isFinite(bpm) && bpm >= MIN_BPM && bpm <= MAX_BPM)) {
      this.app.message(`The tempo must be ${MIN_BPM}–${MAX_BPM} BPM.`, true);
      this.showRun(run);
      return;
    }
    await this.app.busy("Re-analysing the beats…", async () => {
      const changed = await postJSON(`/api/runs/${run.id}/bpm`, { bpm });
      await this.app.openRun(changed, this.app.generationNumber);
    });
  }
}
