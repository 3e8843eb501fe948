// The song and the clock every dancer follows.
//
// Frames are never counted by the page: the frame shown is always
//   (AudioContext.currentTime - start) * fps,
// where start is the context time at which song time 0 played. Pausing
// suspends the AudioContext, which stops its clock; seeking restarts the
// song at a new offset and moves start. So whatever the song does, every
// dancer is at the frame of the sound being played. The song loops over the
// danced part (runs dance at most six minutes; the page says when a song is cut).

export class SongClock {
  constructor() {
    this.context = new AudioContext();
    this.context.suspend();
    this.buffers = new Map(); // decoded songs by key
    this.buffer = null;
    this.source = null;
    this.start = 0; // context time at which song time 0 played
    this.length = 1; // seconds of song that loop (the dance's length)
    this.gain = this.context.createGain();
    this.gain.connect(this.context.destination);
  }

  /** Fetch and decode a song (once per key), then play it from ``offset`` when playing. */
  async load(key, url, length, offset = 0) {
    if (!this.buffers.has(key)) {
      const response = await fetch(url);
      if (!response.ok) throw new Error(`cannot load the song (${response.status})`);
      const bytes = await response.arrayBuffer();
      try {
        this.buffers.set(key, await this.context.decodeAudioData(bytes));
      } catch {
        throw new Error("this browser cannot decode the song");
      }
    }
    this.buffer = this.buffers.get(key);
    this.length = Math.max(0.5, Math.min(length, this.buffer.duration));
    this.seek(offset);
  }

  get playing() {
    return this.context.state === "running";
  }

  /** Song time in seconds, in [0, length). */
  time() {
    const elapsed = this.context.currentTime - this.start;
    return ((elapsed % this.length) + this.length) % this.length;
  }

  /** The frame of the sound being played, at ``fps`` frames per second. */
  frame(fps) {
    return Math.floor(this.time() * fps + 1e-6);
  }

  async play() {
    await this.context.resume();
  }

  async pause() {
    await this.context.suspend();
  }

  /** Jump to ``seconds`` of the song (playing or paused). */
  seek(seconds) {
    if (this.source) {
      this.source.onended = null;
      this.source.stop();
      this.source.disconnect();
    }
    const offset = Math.min(Math.max(seconds, 0), this.length - 1e-3);
    this.start = this.context.currentTime - offset;
    if (!this.buffer) return;
    this.source = this.context.createBufferSource();
    this.source.buffer = this.buffer;
    this.source.loop = true;
    this.source.loopStart = 0;
    this.source.loopEnd = this.length;
    this.source.connect(this.gain);
    this.source.start(this.context.currentTime, offset);
  }
}
