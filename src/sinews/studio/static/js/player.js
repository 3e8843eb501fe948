// The player bar: play/pause, a seek slider and the time, all reading the song clock.

const clockText = (seconds) => {
  const s = Math.max(0, Math.floor(seconds));
  return `${Math.floor(s / 60)}:${String(s % 60).padStart(2, "0")}`;
};

export class Player {
  /**
   * @param {import("./clock.js").SongClock} clock
   * @param {{button: HTMLButtonElement, seek: HTMLInputElement, time: HTMLElement}} elements
   */
  constructor(clock, elements) {
    this.clock = clock;
    this.elements = elements;
    this.seeking = false;
    elements.button.addEventListener("click", () => this.toggle());
    elements.seek.addEventListener("input", () => {
      this.seeking = true;
      this.clock.seek(Number(elements.seek.value));
    });
    elements.seek.addEventListener("change", () => {
      this.seeking = false;
    });
  }

  async play() {
    await this.clock.play();
    this.update();
  }

  async toggle() {
    if (this.clock.playing) await this.clock.pause();
    else await this.clock.play();
    this.update();
  }

  /** Refresh the button, slider and time (called every animation frame). */
  update() {
    const { button, seek, time } = this.elements;
    const playing = this.clock.playing;
    button.textContent = playing ? "❚❚ Pause" : "▶ Play";
    button.setAttribute("aria-pressed", String(playing));
    seek.max = this.clock.length.toFixed(2);
    const now = this.clock.time();
    if (!this.seeking) seek.value = now.toFixed(2);
    time.textContent = `${clockText(now)} / ${clockText(this.clock.length)}`;
  }
}
