// Tap tempo: tap along with the song; the median time between taps gives the BPM.
//
// A series needs at least MIN_TAPS taps; it ends when no tap comes for
// RESET_MS, and then its tempo (if it has one) is handed on. Times are
// performance.now() milliseconds, read when the tap happens.

export const MIN_TAPS = 4;
export const RESET_MS = 2000;

const median = (values) => {
  const sorted = [...values].sort((a, b) => a - b);
  const middle = Math.floor(sorted.length / 2);
  return sorted.length % 2 ? sorted[middle] : (sorted[middle - 1] + sorted[middle]) / 2;
};

export class TapTempo {
  /**
   * @param {(bpm: number) => void} onTempo called when a series of enough taps ends
   * @param {(taps: number, bpm: number | null) => void} onTap called after every tap
   */
  constructor(onTempo, onTap) {
    this.onTempo = onTempo;
    this.onTap = onTap;
    this.times = [];
    this.timer = null;
  }

  /** The tempo of the taps so far, or null with fewer than MIN_TAPS. */
  bpm() {
    if (this.times.length < MIN_TAPS) return null;
    const gaps = this.times.slice(1).map((t, k) => t - this.times[k]);
    return 60000 / median(gaps);
  }

  tap(now = performance.now()) {
    const last = this.times[this.times.length - 1];
    if (last !== undefined && now - last > RESET_MS) this.times = [];
    this.times.push(now);
    this.onTap(this.times.length, this.bpm());
    clearTimeout(this.timer);
    this.timer = setTimeout(() => this.end(), RESET_MS);
  }

  /** The series is over: hand on its tempo, start afresh. */
  end() {
    clearTimeout(this.timer);
    const bpm = this.bpm();
    this.times = [];
    this.onTap(0, null);
    if (bpm !== null) this.onTempo(bpm);
  }
}
