// A dance run's song on the figure page: the replays follow the audio clock.
//
// A run that dances (`run.song`, from GET /api/figures/runs/N) plays its song from
// /api/figures/runs/N/audio on the dancer page's `SongClock`: the replay time is always the
// song time being heard, looping over the trial's seconds (the part of the song the figures
// danced to), so pausing, seeking and playing move sound and figures together. Its beats are
// marked under the seek bar, and the mark of the beat just heard lights up.

import { SongClock } from "../clock.js";

/** How long (s) a beat's mark stays lit after the beat. */
const LIT = 0.12;

export class RunSong {
  /** @param {HTMLCanvasElement} marks the strip under the seek bar that shows the beats */
  constructor(marks) {
    this.marks = marks;
    this.clock = null; // made for the first dance (an AudioContext per page)
    this.song = null; // the run's song JSON while a dance is open, else null
  }

  /** Open ``run``'s song (or none); resolves to whether it dances. */
  async open(run) {
    this.song = run.song || null;
    this.marks.hidden = !this.song;
    if (!this.song) {
      if (this.clock) await this.clock.pause();
      return false;
    }
    this.clock ??= new SongClock();
    await this.clock.load(this.song.id, `/api/figures/runs/${run.id}/audio`, this.song.seconds, 0);
    return true;
  }

  get playing() {
    return Boolean(this.song) && this.clock.playing;
  }

  /** Song time (s) being heard, in [0, the trial's seconds). */
  time() {
    return this.clock.time();
  }

  async play() {
    await this.clock.play();
  }

  async pause() {
    await this.clock.pause();
  }

  seek(seconds) {
    this.clock.seek(seconds);
  }

  /** Draw the beats along the strip, the song's position, and light the beat just heard. */
  draw() {
    if (!this.song) return;
    const canvas = this.marks, ctx = canvas.getContext("2d");
    const width = (canvas.width = canvas.clientWidth || canvas.width), height = canvas.height;
    const { seconds, beats } = this.song, now = this.time();
    const x = (t) => (t / seconds) * (width - 1);
    ctx.clearRect(0, 0, width, height);
    let lit = -1;
    beats.forEach((beat, k) => {
      if (beat <= now && now - beat < LIT) lit = k;
      ctx.fillStyle = k === lit ? "rgb(214,80,40)" : "rgb(150,142,130)";
      ctx.fillRect(Math.round(x(beat)) - (k === lit ? 2 : 1), 0, k === lit ? 4 : 2, height);
    });
    ctx.fillStyle = "rgb(40,90,160)";
    ctx.fillRect(Math.round(x(now)), 0, 1, height);
    this.marks.dataset.lit = String(lit);
  }
}
