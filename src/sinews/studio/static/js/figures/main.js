// The figure page: a generation of lamps, snakes or humanoids replayed in sync, picked by
// hand and bred, or evolved in the background while a plot follows the fitness.
// State lives on `window.figures` (the browser tests read it).

import { download, getJSON, getPack, postFile, postJSON } from "../api.js";
import { RunSong } from "./audio.js";
import { drawNet, prettyProgram } from "./panel.js";
import { drawCross, planarDrawer, View } from "./planar.js";
import { solidDrawer } from "./solid.js";
import { drawPlot } from "./plot.js";
import { exportButtons } from "./exports.js";

const $ = (id) => document.getElementById(id);
const DRAWERS = { planar: planarDrawer, solid: solidDrawer };
const POLL_MS = 1000;
const PANEL_SHARE = 0.22;

const figures = {
  session: null,
  run: null, // the run's JSON (GET /api/figures/runs/N)
  shown: null, // the generation on screen
  pack: null,
  drawer: null,
  order: [],
  picks: new Set(),
  staged: 0,
  timeline: null, // {pack, drawer, k}: the learning timeline on the stage, or null
  playing: true,
  clock: { start: performance.now(), at: 0 },
  frame: 0,
  views: [],
  stageView: null,
  follow: true, // jump to each new generation as it arrives
  song: new RunSong($("beats")), // a dance's song: then the replays follow its audio clock
};
window.figures = figures;

function say(text, error = false) {
  const box = $("message");
  box.hidden = !text;
  box.textContent = text || "";
  box.classList.toggle("error", error);
}

async function attempt(action) {
  try {
    await action();
  } catch (error) {
    say(error.message, true);
  }
}

// -- runs ---------------------------------------------------------------------------------

function runName(run) {
  const task = run.task ? ` ${run.task}` : "";
  return `${run.id}: ${run.kind} ${run.figure}${task} (${run.generations} gen, ${run.status})`;
}

async function refreshRunList(selected) {
  figures.session = await getJSON("/api/figures/session");
  const select = $("runs");
  select.replaceChildren(...figures.session.runs.map((run) => new Option(runName(run), run.id)));
  if (selected !== undefined) select.value = String(selected);
}

async function openRun(id) {
  figures.run = await getJSON(`/api/figures/runs/${id}`);
  figures.picks.clear();
  figures.follow = true;
  history.replaceState(null, "", `/figures?run=${id}`);
  $("runs").value = String(id);
  await openSong();
  showRun();
  const last = figures.run.generations - 1;
  if (last >= 0) await showGeneration(last);
  else clearGrid();
  document.body.classList.remove("starting");
}

/** A dance plays with its song, the replays on its audio clock (paused until Play is pressed:
 * a browser plays sound only after a click). */
async function openSong() {
  const dancing = await figures.song.open(figures.run);
  $("song-name").textContent = dancing ? `♪ ${figures.run.song.name}` : "";
  setPlaying(dancing ? false : figures.playing);
}

function showRun() {
  const run = figures.run;
  const job = run.job;
  const evolving = Boolean(job && job.running);
  document.body.classList.toggle("watching", evolving || run.readOnly);
  document.body.classList.toggle("no-pause", run.readOnly || !evolving);
  $("run-info").textContent = `run ${run.id} · ${run.kind} ${run.figure}${run.task ? " " + run.task : ""}`
    + ` · ${run.population} per generation · ${run.strategy}`;
  const select = $("generation");
  if (select.options.length !== run.generations) {
    select.replaceChildren(...[...Array(run.generations).keys()].map((g) => new Option(String(g), g)));
  }
  if (figures.shown !== null) select.value = String(figures.shown);
  const target = job && job.running ? job.target : Math.max(run.planned, run.generations);
  $("progress").max = Math.max(1, target);
  $("progress").value = run.generations;
  let text = `${run.generations} / ${target} generations`;
  if (run.readOnly) text += " · running in another process (read-only)";
  else if (evolving) text += job.pausing ? " · pausing after this generation" : " · evolving";
  else if (job && job.error) text += ` · stopped: ${job.error}`;
  $("progress-text").textContent = text;
  $("pick-rule").textContent = pickRule(run);
  const sort = $("sort"), keep = sort.value;
  sort.replaceChildren(new Option("fitness", "fitness"), new Option("index", "index"),
    ...run.terms.map((term) => new Option(term, `term:${term}`)));
  sort.value = [...sort.options].some((o) => o.value === keep) ? keep : "fitness";
  drawPlot($("plot"), run.history, run.fitnessLabel, figures.shown);
  showFitness();
  updateBreedBar();
}

/** How picks breed in this run's strategy. */
function pickRule(run) {
  const most = `Click up to ${run.maxPicks} ${run.kind === "gp" ? "programs" : "nets"} to pick them: `;
  if (run.maxPicks === 0) return `This run's strategy (${run.strategy}) takes no picks: it breeds by fitness alone.`;
  if (run.strategy === "gp") {
    return `${most}picks are the parents of the next generation's crossovers (the rest by fitness tournaments).`;
  }
  if (run.strategy === "hybrid") {
    return `${most}picks rank above the rest (the best of them kept, all winning tournaments first), the rest by fitness.`;
  }
  return `${most}picks survive first, the rest by fitness (Alton's hand selection).`;
}

/** The style-weight sliders and phase-in window, rebuilt when the run's spec changes. */
function showFitness() {
  const run = figures.run, spec = run.fitness, key = `${run.id} ${JSON.stringify(spec)}`;
  if (figures.fitnessShown === key) return;
  figures.fitnessShown = key;
  const styles = Object.entries(spec.weights).filter(([name]) => name !== spec.main);
  $("fitness-box").hidden = !styles.length;
  $("weights").replaceChildren(...styles.map(([name, weight]) => {
    const row = document.createElement("label"), slider = document.createElement("input");
    const shown = document.createElement("output");
    Object.assign(slider, { type: "range", min: "0", max: String(Math.max(1, 4 * weight)), value: String(weight) });
    slider.step = String(Math.max(1, 4 * weight) / 100);
    slider.dataset.term = name;
    shown.textContent = weight.toFixed(2);
    slider.addEventListener("input", () => { shown.textContent = Number(slider.value).toFixed(2); });
    row.append(name, slider, shown);
    return row;
  }));
  $("phase-start").value = String(spec.phase_in.start);
  $("phase-full").value = String(spec.phase_in.full);
  const changes = run.fitnessHistory.map((h) => h.until);
  $("fitness-note").textContent = changes.length ? `changed before generation ${changes.join(", ")}` : "";
}

async function poll() {
  const run = figures.run;
  if (run && ((run.job && run.job.running) || run.readOnly || run.status === "running")) {
    await attempt(async () => {
      const before = figures.run.generations;
      figures.run = await getJSON(`/api/figures/runs/${run.id}`);
      showRun();
      const last = figures.run.generations - 1;
      if (figures.run.generations !== before && figures.follow && last >= 0) await showGeneration(last);
      if (!(figures.run.job && figures.run.job.running)) await refreshRunList(run.id);
    });
  }
  setTimeout(poll, POLL_MS);
}

// -- a generation -------------------------------------------------------------------------

function clearGrid() {
  figures.pack = null;
  figures.drawer = null;
  $("grid").replaceChildren();
}

async function showGeneration(generation) {
  const run = figures.run;
  const pack = await getPack(`/api/figures/runs/${run.id}/generations/${generation}`);
  if (figures.run.id !== run.id) return;
  const make = DRAWERS[pack.header.drawer];
  if (!make) throw new Error(`this page cannot draw ${pack.header.drawer} figures yet`);
  figures.pack = pack;
  figures.drawer = make(pack);
  figures.shown = generation;
  figures.follow = generation === figures.run.generations - 1;
  figures.picks.clear();
  $("generation").value = String(generation);
  $("seek").max = String(figures.drawer.frames - 1);
  buildGrid();
  stage(bestIndex());
  drawPlot($("plot"), figures.run.history, figures.run.fitnessLabel, generation);
  updateBreedBar();
  document.body.classList.remove("starting");
}

function bestIndex() {
  const people = figures.pack.header.individuals;
  return people.reduce((best, p, i) => ((p.fitness ?? -Infinity) > (people[best].fitness ?? -Infinity) ? i : best), 0);
}

function sortKey(person) {
  const key = $("sort").value;
  if (key === "index") return -person.index;
  const value = key.startsWith("term:") ? person.terms[key.slice(5)] : person.fitness;
  return value ?? -Infinity;
}

function label(person) {
  const number = (v) => (v === null || v === undefined ? "–" : Math.abs(v) >= 100 ? v.toFixed(0) : v.toFixed(3));
  const terms = Object.entries(person.terms).slice(0, 3).map(([k, v]) => `${k} ${number(v)}`).join(" · ");
  return `#${person.index} <b>${number(person.fitness)}</b>${person.failed ? " failed" : ""}`
    + `<br><span class="terms">${terms}</span>`;
}

function buildGrid() {
  const people = figures.pack.header.individuals;
  figures.order = [...people.keys()].sort((a, b) => sortKey(people[b]) - sortKey(people[a]) || a - b);
  const grid = $("grid");
  grid.style.setProperty("--columns", String(Math.ceil(Math.sqrt(people.length))));
  grid.replaceChildren(...figures.order.map((i) => {
    const person = people[i];
    const cell = document.createElement("div");
    cell.className = "cell";
    cell.dataset.index = String(i);
    cell.dataset.id = String(person.id);
    cell.classList.toggle("was-picked", person.picked);
    cell.classList.toggle("failed", person.failed);
    const canvas = document.createElement("canvas");
    const text = document.createElement("span");
    text.className = "label";
    text.innerHTML = label(person);
    const toStage = document.createElement("button");
    toStage.type = "button";
    toStage.className = "to-stage";
    toStage.textContent = "stage";
    toStage.title = "show it large";
    toStage.addEventListener("click", (event) => { event.stopPropagation(); stage(i); });
    cell.append(canvas, text, toStage);
    cell.addEventListener("click", () => togglePick(i));
    return cell;
  }));
  sizeCanvases();
}

function sizeCanvases() {
  if (!figures.drawer) return;
  const ratio = Math.min(window.devicePixelRatio || 1, 2);
  figures.views = [];
  for (const cell of $("grid").children) {
    const canvas = cell.querySelector("canvas"), i = Number(cell.dataset.index);
    canvas.width = Math.max(160, Math.round(canvas.clientWidth * ratio));
    canvas.height = Math.round((canvas.width * 3) / 4);
    figures.views[i] = figures.drawer.view(i, canvas.width, canvas.height);
  }
  stageView();
  drawAll();
}

function togglePick(i) {
  if (document.body.classList.contains("watching")) return;
  if (figures.picks.has(i)) figures.picks.delete(i);
  else if (figures.picks.size < figures.run.maxPicks) figures.picks.add(i);
  else say(`pick at most ${figures.run.maxPicks} (${figures.run.strategy})`, true);
  for (const cell of $("grid").children) cell.classList.toggle("picked", figures.picks.has(Number(cell.dataset.index)));
  updateBreedBar();
}

function updateBreedBar() {
  const run = figures.run, last = run ? run.generations - 1 : -1;
  const onLast = figures.shown === last;
  $("breed").disabled = !onLast || figures.picks.size === 0;
  $("breed-info").textContent = !run ? "" : onLast
    ? `${figures.picks.size} of at most ${run.maxPicks} picked`
    : "pick in the last generation to breed";
}

// -- the stage ----------------------------------------------------------------------------

/** What the stage shows: a cell of the generation, or the timeline's current best. */
function staged() {
  const line = figures.timeline;
  return line ? { pack: line.pack, drawer: line.drawer, i: line.k }
    : { pack: figures.pack, drawer: figures.drawer, i: figures.staged };
}

function stage(i) {
  figures.staged = i;
  if (figures.timeline) setTimeline(null);
  for (const cell of $("grid").children) cell.classList.toggle("staged", Number(cell.dataset.index) === i);
  describe(figures.pack.header.individuals[i], "Stage");
  stageView();
  drawAll();
}

function describe(person, title) {
  $("stage-title").textContent = `${title}: generation ${person.generation} #${person.index}`;
  const program = $("program");
  program.hidden = !person.program;
  program.textContent = person.program ? prettyProgram(person.program) : "";
  exportsBar.show(person);
  $("terms").replaceChildren(...[["fitness", person.fitness], ...Object.entries(person.terms)].map(([k, v]) => {
    const span = document.createElement("span");
    span.textContent = `${k} ${v === null ? "–" : v.toPrecision(4)}`;
    return span;
  }));
}

function stageView() {
  const { pack, drawer, i } = staged();
  if (!drawer) return;
  const canvas = $("stage"), person = pack.header.individuals[i];
  const band = person.net ? Math.round(PANEL_SHARE * canvas.height) : 0;
  figures.detach?.();
  figures.stageView = drawer.view(i, canvas.width, canvas.height, band);
  figures.detach = drawer.attach?.(canvas, figures.stageView); // 3D: orbit with the mouse
  figures.stageBand = band;
}

// -- the learning timeline: the best of each generation in turn ---------------------------

function setTimeline(pack) {
  figures.timeline = pack ? { pack, drawer: DRAWERS[pack.header.drawer](pack), k: 0 } : null;
  $("timeline").setAttribute("aria-pressed", String(Boolean(pack)));
  $("timeline-seek").hidden = !pack;
  $("timeline-label").textContent = "";
  if (pack) {
    $("timeline-seek").max = String(pack.header.individuals.length - 1);
    timelineAt(0);
  } else if (figures.pack) {
    describe(figures.pack.header.individuals[figures.staged], "Stage");
    stageView();
  }
}

function timelineAt(k) {
  const line = figures.timeline, people = line.pack.header.individuals;
  line.k = k;
  $("timeline-seek").value = String(k);
  $("timeline-label").textContent = `${k + 1} of ${people.length}`;
  describe(people[k], "Learning timeline, best of");
  stageView();
}

// -- playing ------------------------------------------------------------------------------

function currentFrame() {
  const drawer = figures.drawer;
  if (!drawer) return 0;
  const clock = figures.clock;
  const seconds = figures.song.song ? figures.song.time() // a dance: the song being heard
    : figures.playing ? clock.at + (performance.now() - clock.start) / 1000 : clock.at;
  return Math.floor(seconds * drawer.fps + 1e-6) % drawer.frames;
}

function drawAll() {
  const drawer = figures.drawer;
  if (!drawer) return;
  const t = currentFrame();
  const line = figures.timeline;
  if (line && figures.playing && t < figures.frame) { // a replay ended: the next generation's best
    timelineAt((line.k + 1) % line.pack.header.individuals.length);
  }
  figures.frame = t;
  document.body.dataset.frame = String(t);
  for (const cell of $("grid").children) {
    const i = Number(cell.dataset.index), canvas = cell.querySelector("canvas");
    drawer.draw(canvas.getContext("2d"), i, t, figures.views[i]);
  }
  const canvas = $("stage"), ctx = canvas.getContext("2d"), shown = staged();
  const frame = Math.min(t, shown.drawer.frames - 1);
  shown.drawer.draw(ctx, shown.i, frame, figures.stageView);
  const person = shown.pack.header.individuals[shown.i];
  if (person.net) {
    drawNet(ctx, person.net, shown.pack.arrays.net.data, shown.i, frame, shown.drawer.frames,
      shown.pack.header.jointColors, canvas.width, figures.stageBand);
  }
  $("seek").value = String(t);
  $("time").textContent = `${(t / drawer.fps).toFixed(1)} s`;
  figures.song.draw();
}

function tick() {
  if (figures.playing) drawAll();
  requestAnimationFrame(tick);
}

function setPlaying(playing) {
  const clock = figures.clock;
  clock.at = figures.drawer ? currentFrame() / figures.drawer.fps : 0;
  clock.start = performance.now();
  figures.playing = playing;
  if (figures.song.song) (playing ? figures.song.play() : figures.song.pause()).then(drawAll);
  $("play").textContent = playing ? "❚❚ Pause" : "▶ Play";
  $("play").setAttribute("aria-pressed", String(playing));
  drawAll();
}

// -- the new-run form ---------------------------------------------------------------------

/** The form's choices for its controller, figure and task (`form_tasks` on the server). */
function formTask() {
  const byFigure = figures.session.tasks[$("form-controller").value];
  const tasks = byFigure[$("form-figure").value] || {};
  return tasks[$("form-task").value] || {};
}

function fill(select, values) {
  const keep = select.value;
  select.replaceChildren(...values.map((v) => new Option(v, v)));
  if (values.includes(keep)) select.value = keep;
}

function formTasks() {
  const byFigure = figures.session.tasks[$("form-controller").value];
  fill($("form-figure"), Object.keys(byFigure));
  const tasks = byFigure[$("form-figure").value];
  fill($("form-task"), Object.keys(tasks));
  $("form-task-box").hidden = Object.keys(tasks).length < 2;
  const takes = formTask(), axes = takes.axes || "";
  const shown = `${$("form-figure").value} ${$("form-task").value}`;
  if (takes.target && figures.formShown !== shown) { // a new task: its own default target
    [...axes].forEach((axis, k) => { $(`form-target-${axis}`).value = String(takes.target[k]); });
  }
  figures.formShown = shown;
  $("form-target-box").hidden = !takes.target;
  $("form-floor").hidden = !takes.target;
  for (const axis of "xyz") $(`form-target-${axis}`).hidden = !axes.includes(axis);
  $("form-song-box").hidden = !takes.song;
  $("form-lamp-box").hidden = !takes.lamps;
  if (takes.lamps) fill($("form-lamp"), takes.lamps);
  drawFloor();
}

function formSongs(selected) {
  $("form-song").replaceChildren(...figures.session.songs.map((song) => new Option(song.name, song.id)));
  if (selected) $("form-song").value = selected;
}

/** The form's floor: 5 m from just behind the start, the ground 30 px above the bottom. */
function floorView(canvas) {
  const scale = canvas.width / 5;
  return new View(canvas.width, canvas.height, scale, -0.5, (canvas.height - 30) / scale);
}

function drawFloor() {
  const canvas = $("form-floor"), ctx = canvas.getContext("2d");
  const v = floorView(canvas);
  ctx.fillStyle = "rgb(250,248,243)"; ctx.fillRect(0, 0, canvas.width, canvas.height);
  ctx.fillStyle = "rgb(232,228,219)"; ctx.fillRect(0, v.y(0), canvas.width, canvas.height - v.y(0));
  ctx.fillStyle = "rgb(120,114,104)"; ctx.font = "11px system-ui, sans-serif"; ctx.textAlign = "center";
  for (let x = 0; x <= 4; x += 0.5) ctx.fillText(`${x} m`, v.x(x), v.y(0) + 14);
  ctx.fillStyle = "rgb(46,139,87)"; ctx.fillRect(v.x(0) - 1, v.y(0) - 14, 2, 14);
  if ($("form-target-box").hidden) return;
  const x = Number($("form-target-x").value);
  if ((formTask().axes || "").includes("z")) {
    const z = Number($("form-target-z").value);
    ctx.strokeStyle = "rgb(200,40,40)"; ctx.lineWidth = 2;
    ctx.beginPath(); ctx.arc(v.x(x), v.y(z), 6, 0, 2 * Math.PI); ctx.stroke();
  } else {
    drawCross(ctx, v.x(x), v.y(0), 7);
  }
}

function floorClick(event) {
  const canvas = $("form-floor"), box = canvas.getBoundingClientRect();
  const v = floorView(canvas);
  const [x, z] = v.world(((event.clientX - box.left) * canvas.width) / box.width,
    ((event.clientY - box.top) * canvas.height) / box.height);
  $("form-target-x").value = x.toFixed(2);
  if ((formTask().axes || "").includes("z")) $("form-target-z").value = Math.max(0, z).toFixed(2);
  drawFloor();
}

function formBody() {
  const number = (id) => Number($(id).value);
  const body = {
    figure: $("form-figure").value,
    controller: $("form-controller").value,
    population: number("form-population"),
    generations: number("form-generations"),
    seconds: number("form-seconds"),
    seed: number("form-seed"),
    task: $("form-task").value,
  };
  const takes = formTask(), axes = takes.axes || "";
  if (takes.target) body.target = axes.length === 1 ? number("form-target-x") : [...axes].map((a) => number(`form-target-${a}`));
  if (takes.song) body.song = $("form-song").value;
  if (takes.lamps) body.lamp = $("form-lamp").value;
  return body;
}

// -- wiring -------------------------------------------------------------------------------

async function start() {
  await refreshRunList();
  const session = figures.session;
  $("form-controller").replaceChildren(...session.controllers.map((c) => new Option(c, c)));
  formSongs();
  formTasks();
  const asked = Number(new URLSearchParams(location.search).get("run"));
  const first = session.runs.some((r) => r.id === asked) ? asked : session.runs[0]?.id;
  if (first === undefined) {
    $("new-run").hidden = false;
    document.body.classList.remove("starting");
    say("No figure run yet: choose a figure and start one.");
  } else {
    await openRun(first);
  }
}

$("runs").addEventListener("change", () => attempt(() => openRun(Number($("runs").value))));
$("generation").addEventListener("change", () => attempt(() => showGeneration(Number($("generation").value))));
$("sort").addEventListener("change", () => figures.pack && buildGrid());
$("play").addEventListener("click", () => setPlaying(!figures.playing));
$("seek").addEventListener("input", () => {
  figures.clock.at = Number($("seek").value) / (figures.drawer ? figures.drawer.fps : 1);
  figures.clock.start = performance.now();
  if (figures.song.song) figures.song.seek(figures.clock.at);
  drawAll();
});
$("clear-picks").addEventListener("click", () => { figures.picks.clear(); togglePick(-1); });
$("breed").addEventListener("click", () => attempt(async () => {
  const run = figures.run, picks = [...figures.picks];
  document.body.classList.add("busy");
  say(`breeding generation ${figures.shown + 1} from ${picks.length} pick(s)…`);
  try {
    figures.run = await postJSON(`/api/figures/runs/${run.id}/generations/${figures.shown}/breed`, { picks });
    showRun();
    await showGeneration(figures.run.generations - 1);
    say("");
  } finally {
    document.body.classList.remove("busy");
  }
}));
$("evolve").addEventListener("click", () => attempt(async () => {
  figures.run = await postJSON(`/api/figures/runs/${figures.run.id}/evolve`, { generations: Number($("more").value) });
  figures.follow = true;
  showRun();
}));
$("pause").addEventListener("click", () => attempt(async () => {
  figures.run = await postJSON(`/api/figures/runs/${figures.run.id}/pause`, {});
  showRun();
}));
$("show-form").addEventListener("click", () => { $("new-run").hidden = false; drawFloor(); });
$("hide-form").addEventListener("click", () => { $("new-run").hidden = true; });
for (const id of ["form-figure", "form-controller", "form-task"]) $(id).addEventListener("change", formTasks);
for (const id of ["form-target-x", "form-target-z"]) $(id).addEventListener("input", drawFloor);
$("form-upload").addEventListener("change", () => attempt(async () => { // the dancer page's upload
  const file = $("form-upload").files[0];
  $("form-upload").value = "";
  if (!file) return;
  say(`analysing ${file.name}…`);
  const song = await postFile("/api/songs", file);
  await refreshRunList(figures.run?.id);
  formSongs(song.id);
  say(`${song.name}: ${song.tempo.toFixed(1)} BPM, ${song.duration.toFixed(1)} s`);
}));
$("form-floor").addEventListener("click", floorClick);
$("new-run").addEventListener("submit", (event) => {
  event.preventDefault();
  attempt(async () => {
    const run = await postJSON("/api/figures/runs", formBody());
    $("new-run").hidden = true;
    say(`run ${run.id} started: evolving ${run.job.target} generations`);
    clearGrid();
    figures.shown = null;
    await refreshRunList(run.id);
    figures.run = run;
    figures.follow = true;
    history.replaceState(null, "", `/figures?run=${run.id}`);
    await openSong();
    showRun();
  });
});
$("apply-fitness").addEventListener("click", () => attempt(async () => {
  const weights = {};
  for (const slider of $("weights").querySelectorAll("input")) weights[slider.dataset.term] = Number(slider.value);
  const phaseIn = [Number($("phase-start").value), Number($("phase-full").value)];
  figures.run = await postJSON(`/api/figures/runs/${figures.run.id}/fitness`, { weights, phaseIn });
  showRun();
  say(`the new weights score generation ${figures.run.generations} on`);
}));
$("timeline").addEventListener("click", () => attempt(async () => {
  if (figures.timeline) setTimeline(null);
  else setTimeline(await getPack(`/api/figures/runs/${figures.run.id}/timeline`));
  drawAll();
}));
$("timeline-seek").addEventListener("input", () => { timelineAt(Number($("timeline-seek").value)); drawAll(); });
$("timeline-mp4").addEventListener("click", () => attempt(async () => {
  say("drawing the learning timeline as a video…");
  say(`saved ${await download(`/api/figures/runs/${figures.run.id}/timeline.mp4`)}`);
}));
const exportsBar = exportButtons({
  run: () => figures.run,
  staged: () => { const { pack, i } = staged(); return pack ? pack.header.individuals[i] : null; },
  say,
  attempt,
});
window.addEventListener("resize", () => sizeCanvases());

attempt(start).then(() => {
  requestAnimationFrame(tick);
  setTimeout(poll, POLL_MS);
});
