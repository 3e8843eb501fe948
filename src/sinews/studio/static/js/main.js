// The studio page: wires the grid, stage, lineage, songs and player to the server.
// Everything the page shows is drawn at the song clock's frame, every animation frame.

import { download, geneQuery, getJSON, getPack, postJSON } from "./api.js";
import { SongClock } from "./clock.js";
import { Grid } from "./grid.js";
import { Lineage } from "./lineage.js";
import { LiveLink } from "./live.js";
import { Player } from "./player.js";
import { Songs } from "./songs.js";
import { Stage } from "./stage.js";

const $ = (id) => document.getElementById(id);

class Studio {
  constructor() {
    this.clock = new SongClock();
    this.player = new Player(this.clock, { button: $("play"), seek: $("seek"), time: $("time") });
    this.grid = new Grid($("grid"), {
      onPicks: (picks) => this.showPicks(picks),
      onStage: (dancer) => this.run && this.stageDancer(dancer.id),
    });
    this.link = new LiveLink((text) => this.message(text, true));
    this.stage = new Stage($("stage"), this.link, {
      play: () => this.player.play(),
      onLive: (live) => {
        $("stage-box").classList.toggle("live", live);
      },
    });
    this.lineage = new Lineage($("lineage"), (person) => this.goTo(person));
    this.songs = new Songs(
      { select: $("song"), upload: $("upload"), tempo: $("tempo"), half: $("tempo-half"),
        double: $("tempo-double"), auto: $("tempo-auto"), form: $("tempo-form"),
        bpm: $("tempo-bpm"), tap: $("tempo-tap"), shift: $("beat-shift"),
        earlier: $("shift-earlier"), later: $("shift-later") },
      this,
    );
    this.run = null;
    this.generation = null;
    this.generationNumber = 0;
    this.staged = null; // id of the dancer on the stage
    this.genes = {}; // body genes changed by the sliders
    this.fps = 60;
    $("breed").addEventListener("click", () => this.breed());
    $("clear-picks").addEventListener("click", () => this.grid.clearPicks());
    $("sheet").addEventListener("click", () => this.sheet());
    $("runs").addEventListener("change", () => this.openRunById(Number($("runs").value)));
    $("new-run").addEventListener("click", () => this.newRun());
    $("overlay").addEventListener("change", () => {
      this.stage.overlay = $("overlay").checked;
    });
    $("mutation").addEventListener("input", () => this.showMutation());
    $("reset-genes").addEventListener("click", () => this.resetGenes());
    for (const button of document.querySelectorAll("[data-export]")) {
      button.addEventListener("click", () => this.exportDancer(button.dataset.export));
    }
    addEventListener("resize", () => {
      this.grid.resize();
      this.stage.resize();
    });
  }

  async start() {
    this.message("Warming up: the first generation is being simulated (a first start also compiles the simulator)…");
    const session = await getJSON("/api/session");
    this.maxUpload = session.maxUpload;
    const mutation = $("mutation");
    mutation.max = session.mutation.max;
    mutation.value = session.mutation.default;
    this.showMutation();
    this.makeSliders(session.sliders);
    this.stage.resize();
    const wanted = this.wantedPlace();
    this.run = await getJSON(`/api/runs/${wanted ? wanted.run : session.run}`).catch(() => null);
    if (!this.run) this.run = await getJSON(`/api/runs/${session.run}`);
    await this.songs.refresh(session.songs);
    const generation = wanted && wanted.run === this.run.id && wanted.generation <= this.run.last
      ? wanted.generation : this.run.last;
    await this.openRun(this.run, generation);
    document.body.classList.remove("starting");
    this.message("");
    const tick = () => {
      this.draw();
      requestAnimationFrame(tick);
    };
    requestAnimationFrame(tick);
  }

  /** The run and generation named in the address (#run=3&gen=5): a reload comes back there. */
  wantedPlace() {
    const params = new URLSearchParams(location.hash.slice(1));
    const run = Number(params.get("run"));
    const generation = Number(params.get("gen"));
    if (!Number.isInteger(run) || run < 1 || !Number.isInteger(generation) || generation < 0) return null;
    return { run, generation };
  }

  draw() {
    const frame = this.clock.frame(this.fps);
    this.grid.draw(frame);
    this.stage.draw(frame);
    this.player.update();
    document.body.dataset.frame = frame;
  }

  message(text, error = false) {
    const box = $("message");
    box.textContent = text;
    box.hidden = !text;
    box.classList.toggle("error", error);
    clearTimeout(this.messageTimer);
    if (!error && text) this.messageTimer = setTimeout(() => this.message(""), 8000);
  }

  /** Run ``work`` with ``label`` showing; a failure shows its one-line message. */
  async busy(label, work) {
    document.body.classList.add("busy");
    this.message(label);
    try {
      await work();
      if ($("message").textContent === label) this.message("");
    } catch (error) {
      this.message(error.message, true);
    } finally {
      document.body.classList.remove("busy");
    }
  }

  async openRunById(id) {
    await this.busy(`Opening run ${id}…`, async () => this.openRun(await getJSON(`/api/runs/${id}`)));
  }

  /** Show ``run`` at ``generation`` (default: its last), keeping the song position. */
  async openRun(run, generation = run.last) {
    const songChanged = !this.run || this.run.song.id !== run.song.id || !this.clock.buffer;
    this.run = run;
    this.songs.showRun(run);
    $("cut").textContent = run.cut || "";
    $("cut").hidden = !run.cut;
    const offset = songChanged ? 0 : this.clock.time();
    await this.clock.load(run.song.id, `/api/runs/${run.id}/audio`, run.seconds, offset);
    await this.refreshRuns();
    await this.showGeneration(generation, true);
  }

  async newRun() {
    await this.busy("Starting a new run…", async () => {
      const run = await postJSON("/api/runs", { song: $("song").value });
      this.staged = null;
      await this.openRun(run);
    });
  }

  async refreshRuns() {
    const runs = await getJSON("/api/runs");
    $("runs").replaceChildren(
      ...runs.map((run) => {
        const option = document.createElement("option");
        option.value = run.id;
        option.textContent = `run ${run.id} · ${run.song.name} · ${run.last + 1} gen`;
        return option;
      }),
    );
    $("runs").value = this.run.id;
  }

  async showGeneration(number, restage = false) {
    const pack = await getPack(`/api/runs/${this.run.id}/generations/${number}`);
    this.setGeneration(pack);
    const dancers = pack.header.dancers;
    if (restage || !dancers.some((d) => d.id === this.staged)) {
      if (!dancers.some((d) => d.id === this.staged)) this.staged = dancers[0].id;
      await this.stageDancer(this.staged);
    } else {
      this.grid.setStaged(this.staged);
    }
  }

  setGeneration(pack) {
    this.generation = pack;
    this.generationNumber = pack.header.generation;
    history.replaceState(null, "", `#run=${this.run.id}&gen=${this.generationNumber}`);
    this.fps = pack.header.fps;
    this.grid.show(pack);
    this.grid.setStaged(this.staged);
    if (pack.header.generation === this.run.last) {
      $("mutation").value = pack.header.mutation;
      this.showMutation();
    }
    this.showGenerations();
  }

  showGenerations() {
    const list = $("generations");
    const buttons = [];
    for (let g = 0; g <= this.run.last; g++) {
      const button = document.createElement("button");
      button.type = "button";
      button.textContent = g;
      button.dataset.generation = g;
      button.title = g === 0 ? "generation 0: the random start" : `generation ${g}`;
      if (g === this.generationNumber) button.setAttribute("aria-current", "true");
      button.addEventListener("click", () =>
        this.busy(`Loading generation ${g}…`, () => this.showGeneration(g)),
      );
      buttons.push(button);
    }
    list.replaceChildren(...buttons);
    const origin = this.run.branchOf;
    $("run-info").textContent = origin
      ? `run ${this.run.id}, branched from generation ${origin[1]} of run ${origin[0]}`
      : `run ${this.run.id}`;
    this.showPicks(this.grid.picks);
  }

  showPicks(picks) {
    const n = picks.size;
    const older = this.run && this.generationNumber < this.run.last;
    let label = n === 0 ? "New random generation" : n === 1 ? `Mutate #${[...picks][0]}` : `Breed ${n} picks`;
    if (older) label += " (as a branch)";
    $("breed").textContent = label;
    $("breed").title = older
      ? "breeding from an earlier generation starts a new run from it; this run stays as it is"
      : "breed the next generation from the picked dancers";
  }

  showMutation() {
    $("mutation-value").textContent = Number($("mutation").value).toFixed(2);
  }

  async breed() {
    const run = this.run;
    const picks = [...this.grid.picks].sort((a, b) => a - b);
    await this.busy("Breeding…", async () => {
      const url = `/api/runs/${run.id}/generations/${this.generationNumber}/breed`;
      const pack = await getPack(url, { picks, mutation: Number($("mutation").value) });
      const timing = pack.response.headers.get("Server-Timing") || "";
      this.lastBreedMs = Number((timing.match(/dur=([\d.]+)/) || [])[1]);
      if (pack.header.run !== run.id) {
        this.run = await getJSON(`/api/runs/${pack.header.run}`);
        await this.refreshRuns();
        this.message(`Branched: run ${this.run.id} continues from generation ${this.generationNumber} of run ${run.id}.`);
      } else {
        this.run.last = pack.header.generation;
        await this.refreshRuns();
      }
      this.setGeneration(pack);
      $("breed-info").textContent = `bred in ${Math.round(this.lastBreedMs)} ms`;
      // the staged dancer belongs to the old generation: stage a child, so exports are of it
      this.staged = pack.header.dancers[0].id;
      await this.stageDancer(this.staged);
    });
  }

  /** Put dancer ``id`` on the stage (with the sliders' genes) and show its lineage. */
  async stageDancer(id, genes = {}) {
    const pack = await getPack(`/api/dancers/${id}/stage${geneQuery(genes)}`);
    this.staged = id;
    this.genes = genes;
    this.stage.show(pack, genes);
    this.grid.setStaged(id);
    const { header } = pack;
    $("stage-title").textContent = `Stage: gen ${header.generation} #${header.index}`;
    for (const input of document.querySelectorAll("#sliders input")) {
      input.value = header.genes[input.name];
      input.nextElementSibling.textContent = Number(input.value).toFixed(2);
    }
    this.lineage.show(await getJSON(`/api/dancers/${id}/lineage`));
  }

  async goTo(person) {
    await this.busy(`Going to generation ${person.generation}…`, async () => {
      this.staged = person.id;
      if (person.run !== this.run.id) await this.openRun(await getJSON(`/api/runs/${person.run}`), person.generation);
      else await this.showGeneration(person.generation, true);
    });
  }

  makeSliders(names) {
    const box = $("sliders");
    for (const name of names) {
      const label = document.createElement("label");
      label.textContent = name.replace("_", " ");
      const input = document.createElement("input");
      Object.assign(input, { type: "range", min: 0, max: 1, step: 0.01, name });
      const value = document.createElement("output");
      input.addEventListener("input", () => {
        value.textContent = Number(input.value).toFixed(2);
        clearTimeout(this.geneTimer);
        this.geneTimer = setTimeout(() => this.changeGenes(), 120);
      });
      label.append(input, value);
      box.append(label);
    }
  }

  async changeGenes() {
    const genes = {};
    for (const input of document.querySelectorAll("#sliders input")) genes[input.name] = Number(input.value);
    await this.busy("", () => this.stageDancer(this.staged, genes));
  }

  async resetGenes() {
    await this.busy("", () => this.stageDancer(this.staged, {}));
  }

  async exportDancer(kind) {
    const what = { json: "the genome", gif: "a GIF (first 20 s)", mp4: "an MP4 with the song" }[kind];
    await this.busy(`Making ${what}…`, async () => {
      const name = await download(`/api/dancers/${this.staged}/export.${kind}${geneQuery(this.genes)}`);
      this.message(`Saved ${name}`);
    });
  }

  async sheet() {
    const frame = this.clock.frame(this.fps);
    await this.busy("Drawing the contact sheet…", async () => {
      const url = `/api/runs/${this.run.id}/generations/${this.generationNumber}/sheet.png?frame=${frame}`;
      this.message(`Saved ${await download(url)}`);
    });
  }
}

const studio = new Studio();
window.studio = studio; // for the browser tests and the curious
studio.start().catch((error) => studio.message(error.message, true));
