// The Exploration page: a simulated robot explores a map it does not know with a 2D range
// sensor, and the floor plan follows its growing map (dissertation § 3.5, Fig. 3.40; the
// browser's `ksmcmc explore`). The robot (`Explorer`) and the chain (`Mapper`) run in a Web
// Worker (lib/explore-worker.js): every `update every` metres the chain takes the robot's map
// with `Mapper.updateMap` and goes on from its world. This thread only draws the pictures the
// worker sends, at most one per animation frame, with the robot's path over them.

import init, { version } from './pkg/ksmcmc_explore.js';
import { parseSeed, onDroppedFiles, readPickedMap } from './lib/files.js';
import { SampleList, fetchSampleMap } from './lib/samples.js';
import { formatNumber } from './lib/plot.js';
import { messages } from './lib/messages.js';
import { RemoteChain } from './lib/remote-chain.js';

/** The most pixels per cell the worker draws (more only costs time per frame). */
const MAX_SCALE = 3;
/** The robot's colour (its disc, its sensor range and its path). */
const ROBOT = '#e8590c';

const $ = (id) => document.getElementById(id);
const ui = {
  message: $('message'), messageText: $('message-text'), messageClose: $('message-close'),
  status: $('status'), version: $('version'),
  run: $('run'), reset: $('reset'), speed: $('speed'), speedValue: $('speed-value'),
  updateEvery: $('update-every'), range: $('range'), seed: $('seed'),
  sampleForm: $('sample-form'), sample: $('sample'), sampleLoad: $('sample-load'), sampleHint: $('sample-hint'),
  file: $('file'), plan: $('plan'), labels: $('labels'), path: $('path'),
  stage: $('stage'), canvas: $('map'), mapName: $('map-name'), stats: $('stats'),
  stat: {
    driven: $('stat-driven'), updates: $('stat-updates'), seen: $('stat-seen'), units: $('stat-units'),
    k: $('stat-k'), iteration: $('stat-iteration'), changed: $('stat-changed'), phase: $('stat-phase'),
  },
};

const { showError, clearError, say, attempt, loadWasm } = messages(ui);

const state = {
  ready: false,
  /** The robot and the chain in their worker (a RemoteChain), and their numbers as last reported. */
  worker: null,
  stats: null,
  running: false,
  /** The sample list, with the description of the picked sample. */
  sampleList: new SampleList(ui.sample, ui.sampleHint, '(an opened map)'),
  sample: null,
  name: '',
  /** What the robot was started with: { seed, rangeM }; the update interval and the speed now. */
  args: null,
  updateEveryM: 10,
  speed: 8,
  /** Metres per cell of the true map (from the worker). */
  resolution: 0.05,
  /** The scan positions so far, flat [x0, y0, x1, y1, ...]: the robot's path. */
  path: [],
  /** The path drawn so far on its own layer (a canvas at the picture's size), in points. */
  pathLayer: null,
  pathDrawn: 0,
  raf: 0,
  /** A picture is wanted, one is on its way, one waits to be drawn, and the last one shown. */
  redrawPending: false,
  inFlight: false,
  picture: null,
  shown: null,
  /** Pixels per cell the worker draws at, and the canvas's width on screen (CSS pixels). */
  scale: 1,
  shownWidth: 1,
  /** Pictures drawn while running. */
  frames: 0,
};

// ---------------------------------------------------------------- settings

/** The robot's settings in the form; throws, saying which is wrong. */
function robotArgs() {
  const seed = parseSeed(ui.seed.value);
  const rangeM = Number(ui.range.value);
  if (!(Number.isFinite(rangeM) && rangeM > 0 && rangeM <= 100)) {
    throw new Error(`Sensor range: "${ui.range.value}" is not a number of metres from above 0 to 100.`);
  }
  return { seed, rangeM };
}

/** Reads the update interval; an error keeps the last good one. */
function readUpdateEvery() {
  const m = Number(ui.updateEvery.value);
  if (!(Number.isFinite(m) && m > 0 && m <= 1000)) {
    throw new Error(`Update every: "${ui.updateEvery.value}" is not a number of metres from above 0 to 1000 (the last good value, ${state.updateEveryM} m, stays).`);
  }
  state.updateEveryM = m;
}

function setSpeed(value) {
  const s = Math.min(64, Math.max(1, Math.round(Number(value)) || 1));
  state.speed = s;
  ui.speed.value = String(s);
  ui.speedValue.textContent = String(s);
}

// ---------------------------------------------------------------- the worker

/** Takes on numbers from a reply, unless later ones are already here. */
function takeStats(stats) {
  if (!state.stats || stats.seq > state.stats.seq) state.stats = stats;
}

/** A new exploration (a new map, or Reset): the path starts over and the picture follows. */
function adopt(stats, args) {
  stopped();
  state.stats = stats;
  state.args = args;
  state.resolution = stats.resolution;
  state.path = [];
  state.pathLayer = null;
  state.pathDrawn = 0;
  state.picture?.picture.close();
  state.picture = null;
  // The last picture is of the old exploration (maybe of another map): not drawn again.
  state.shown?.close();
  state.shown = null;
  ui.canvas.getContext('2d').clearRect(0, 0, ui.canvas.width, ui.canvas.height);
  state.frames = 0;
  for (const b of [ui.run, ui.reset]) b.disabled = false;
  fit();
  updateStats();
  requestRedraw();
}

/** Loads a true map (`source`, as lib/map-source.js reads it) and puts a robot on it. */
async function setTruth(source, { name, label, sample = null }) {
  const args = robotArgs();
  const stats = await state.worker.call('load', { source, ...args });
  state.name = name;
  state.sample = sample;
  ui.mapName.textContent = `· ${label}`;
  state.sampleList.show(sample);
  adopt(stats, args);
  clearError();
  say(`${label}: ${stats.width} × ${stats.height} cells, ${formatNumber(stats.truthFree)} of them free. The robot stands at (${stats.robot.join(', ')}). Press Start (or Space).`);
}

function play() {
  if (!state.stats || state.running) return;
  try {
    readUpdateEvery();
  } catch (err) {
    showError(err);
    return;
  }
  state.running = true;
  ui.run.textContent = 'Pause';
  document.documentElement.dataset.running = 'true';
  say('Exploring. Space pauses.');
  state.worker.call('play').then(takeStats, showError);
  requestRedraw();
}

/** The page's side of stopping: the button and the flag. */
function stopped() {
  state.running = false;
  ui.run.textContent = 'Start';
  document.documentElement.dataset.running = 'false';
}

function pause() {
  if (!state.running) return;
  stopped();
  state.worker.call('pause').then((stats) => {
    takeStats(stats);
    say(`Paused after ${formatNumber(stats.travelledM, 1)} m.`);
    requestRedraw();
  }, showError);
}

function toggle() {
  if (state.running) pause();
  else play();
}

/** Puts the robot back at its start, with the seed and range in the form; no chain until it has driven. */
function reset() {
  if (!state.stats) return;
  attempt(async () => {
    const wasRunning = state.running;
    const args = robotArgs();
    adopt(await state.worker.call('reset', args), args);
    clearError();
    say(`Started over with seed ${ui.seed.value.trim()}.`);
    if (wasRunning) play();
  });
}

/** The worker stopped: the chain settled on the robot's last map. */
function settled(stats) {
  takeStats(stats);
  stopped();
  const c = stats.chain;
  say(
    `Explored ${formatNumber(stats.travelledM, 1)} m with ${stats.updates} updates; the chain settled at iteration ` +
      `${formatNumber(c.settledAt)} with ${c.bestUnits} units, K(W,M) ${formatNumber(c.bestPredictionRate, 4)}. Start runs on.`,
  );
  requestRedraw();
}

/** The worker stopped because the robot or the chain failed. */
function failed(message, stats) {
  if (stats) takeStats(stats);
  stopped();
  showError(new Error(message));
  requestRedraw();
}

// ---------------------------------------------------------------- frames

function requestRedraw() {
  state.redrawPending = true;
  schedule();
}

function schedule() {
  if (!state.raf) state.raf = requestAnimationFrame(frame);
}

/** Asks the worker for a picture (the robot drives `speed` cells for it while running). */
function requestPicture() {
  if (state.inFlight || !state.stats) return;
  state.inFlight = true;
  state.redrawPending = false;
  const asked = {
    generation: state.stats.generation,
    scale: state.scale,
    plan: ui.plan.checked,
    labels: ui.labels.checked,
    speed: state.speed,
    updateEveryM: state.updateEveryM,
    scanFrom: state.path.length / 2,
  };
  state.worker.call('frame', asked).then(
    (result) => {
      state.inFlight = false;
      if (!result || result.stats.generation !== state.stats.generation) {
        result?.picture.close();
        if (state.running || state.redrawPending) schedule();
        return;
      }
      if (asked.scanFrom === state.path.length / 2) {
        for (const v of result.scans) state.path.push(v);
      }
      state.picture?.picture.close();
      state.picture = result;
      schedule();
    },
    (err) => {
      state.inFlight = false;
      stopped();
      showError(err);
    },
  );
}

/** One animation frame: draws the picture that came, and asks for the next while running. */
function frame() {
  state.raf = 0;
  if (state.picture) {
    const { stats, picture } = state.picture;
    state.picture = null;
    takeStats(stats);
    state.shown?.close();
    state.shown = picture;
    if (stats.running) state.frames++;
    draw();
    updateStats();
  }
  if (state.running || state.redrawPending) requestPicture();
}

/** The picture, the robot's path, its range and itself. */
function draw() {
  const bitmap = state.shown;
  const s = state.stats;
  if (!bitmap || !s) return;
  const c = ui.canvas;
  if (c.width !== bitmap.width || c.height !== bitmap.height) {
    c.width = bitmap.width;
    c.height = bitmap.height;
  }
  const ctx = c.getContext('2d');
  ctx.clearRect(0, 0, c.width, c.height);
  ctx.drawImage(bitmap, 0, 0);
  const k = bitmap.width / s.width;
  // Screen pixels → canvas pixels, for line widths that look the same at any size.
  const px = c.width / state.shownWidth;
  const at = (x, y) => [(x + 0.5) * k, (y + 0.5) * k];
  const [rx, ry] = at(...s.robot);
  if (ui.path.checked && state.path.length >= 2) {
    extendPath(k, px);
    ctx.drawImage(state.pathLayer, 0, 0);
    const n = state.path.length;
    ctx.beginPath();
    ctx.moveTo(...at(state.path[n - 2], state.path[n - 1]));
    ctx.lineTo(rx, ry);
    ctx.strokeStyle = ROBOT;
    ctx.lineWidth = 2 * px;
    ctx.stroke();
  }
  const range = (state.args.rangeM / state.resolution) * k;
  ctx.beginPath();
  ctx.arc(rx, ry, range, 0, 2 * Math.PI);
  ctx.setLineDash([6 * px, 4 * px]);
  ctx.strokeStyle = ROBOT;
  ctx.lineWidth = 1.5 * px;
  ctx.stroke();
  ctx.setLineDash([]);
  ctx.beginPath();
  ctx.arc(rx, ry, 5 * px, 0, 2 * Math.PI);
  ctx.fillStyle = ROBOT;
  ctx.fill();
  ctx.lineWidth = 2 * px;
  ctx.strokeStyle = '#fff';
  ctx.stroke();
}

/**
 * Draws the path's new segments on its layer (the whole path again when the layer's size
 * changed): a long exploration has thousands of scans, and each frame adds a few.
 */
function extendPath(k, px) {
  const c = ui.canvas;
  let layer = state.pathLayer;
  if (!layer || layer.width !== c.width || layer.height !== c.height || state.pathDrawn > state.path.length / 2) {
    layer ??= document.createElement('canvas');
    layer.width = c.width;
    layer.height = c.height;
    state.pathLayer = layer;
    state.pathDrawn = 0;
  }
  const points = state.path.length / 2;
  if (state.pathDrawn >= points) return;
  const ctx = layer.getContext('2d');
  const from = Math.max(0, state.pathDrawn - 1);
  ctx.beginPath();
  ctx.moveTo((state.path[2 * from] + 0.5) * k, (state.path[2 * from + 1] + 0.5) * k);
  for (let i = from + 1; i < points; i++) ctx.lineTo((state.path[2 * i] + 0.5) * k, (state.path[2 * i + 1] + 0.5) * k);
  ctx.strokeStyle = ROBOT;
  ctx.lineWidth = 2 * px;
  ctx.lineJoin = 'round';
  ctx.globalAlpha = 0.85;
  ctx.stroke();
  state.pathDrawn = points;
}

/** "12.5 %" of a share. */
function percent(share) {
  return `${formatNumber(100 * share, 1)} %`;
}

function updateStats() {
  const s = state.stats;
  if (!s) return;
  const c = s.chain;
  const t = ui.stat;
  t.driven.textContent = `${formatNumber(s.travelledM, 1)} m`;
  t.updates.textContent = c ? formatNumber(s.updates) : `– (the chain starts at ${formatNumber(state.updateEveryM, 1)} m)`;
  t.seen.textContent = `${percent(s.truthFree ? s.seenFree / s.truthFree : 0)} (${formatNumber(s.seenFree)})`;
  t.units.textContent = c ? String(c.bestUnits) : '–';
  t.k.textContent = c ? formatNumber(c.bestPredictionRate, 4) : '–';
  t.iteration.textContent = c ? formatNumber(c.iteration) : '–';
  t.changed.textContent = s.lastChanged !== null
    ? `${formatNumber(s.lastChanged)} cells (${formatNumber(s.lastUpdateMs)} ms)`
    : c ? `the chain started (${formatNumber(s.lastUpdateMs)} ms)` : '–';
  const r = s.renewal;
  const kept = r?.done
    ? `; kept the ${r.adopted ? 'fresh' : 'warm'} chain (K(W,M) ${formatNumber(r.adopted ? r.fresh.predictionRate : r.warm.predictionRate, 4)}, ` +
      `the ${r.adopted ? 'warm' : 'fresh'} one's ${formatNumber(r.adopted ? r.warm.predictionRate : r.fresh.predictionRate, 4)})`
    : '';
  t.phase.textContent = !c
    ? 'exploring; no chain yet'
    : !s.finished
      ? 'exploring; the chain follows'
      : r && !r.done
        ? `explored; the warm chain under the whole-map table and a fresh one, ${formatNumber(r.ran)} of ${formatNumber(r.iterations)} iterations each`
        : c.settledAt !== null
          ? `explored${kept}; settled at iteration ${formatNumber(c.settledAt)}`
          : `explored${kept}; the chain runs until it settles`;
  ui.canvas.setAttribute(
    'aria-label',
    `The robot's map of ${state.name || 'the map'}: ${formatNumber(s.travelledM, 1)} m driven, ${percent(s.truthFree ? s.seenFree / s.truthFree : 0)} of the free cells seen` +
      (c ? `, a floor plan of ${c.bestUnits} units after ${s.updates} updates` : ''),
  );
}

/**
 * Sizes the canvas on screen to fit the stage, and picks the drawing scale: enough pixels per
 * cell for the screen (at most MAX_SCALE).
 */
function fit() {
  const s = state.stats;
  if (!s) return;
  const box = ui.stage.getBoundingClientRect();
  const availW = Math.max(64, box.width - 16);
  const availH = Math.max(200, Math.min(window.innerHeight * 0.7, 1200));
  const k = Math.min(availW / s.width, availH / s.height);
  state.shownWidth = Math.max(1, Math.round(s.width * k));
  ui.canvas.style.width = `${state.shownWidth}px`;
  ui.canvas.style.height = `${Math.max(1, Math.round(s.height * k))}px`;
  const dpr = globalThis.devicePixelRatio || 1;
  const scale = Math.min(MAX_SCALE, Math.max(1, Math.ceil(k * dpr - 0.01)));
  ui.canvas.classList.toggle('smooth', scale >= k * dpr);
  if (scale !== state.scale) {
    state.scale = scale;
    requestRedraw();
  }
  draw();
}

// ---------------------------------------------------------------- maps

async function loadSample(name) {
  state.sampleList.find(name);
  await setTruth(await fetchSampleMap(name), { name, label: name, sample: name });
}

/** Loads a true map from the picked files: one image, or a map.yaml with the image it names. */
async function openFiles(fileList) {
  const { source, name, label } = await readPickedMap(fileList, 'auto');
  await setTruth(source, { name, label });
}

// ---------------------------------------------------------------- wiring

function onKey(e) {
  const t = e.target;
  if (e.defaultPrevented || e.ctrlKey || e.metaKey || e.altKey || t.closest?.('input, textarea, select, [contenteditable]')) return;
  const key = e.key.toLowerCase();
  // Space on a focused button presses that button; elsewhere it starts and pauses.
  if (key === ' ' && t.closest?.('button, a, summary')) return;
  const flip = (box) => () => {
    box.checked = !box.checked;
    requestRedraw();
  };
  const actions = { ' ': toggle, r: reset, f: flip(ui.plan), l: flip(ui.labels), p: flip(ui.path) };
  const action = actions[key];
  if (!action || !state.ready) return;
  e.preventDefault();
  action();
}

function wire() {
  ui.run.addEventListener('click', toggle);
  ui.reset.addEventListener('click', reset);
  ui.speed.addEventListener('input', () => setSpeed(ui.speed.value));
  ui.updateEvery.addEventListener('change', () =>
    attempt(() => {
      readUpdateEvery();
      updateStats();
    }),
  );
  ui.sampleForm.addEventListener('submit', (e) => {
    e.preventDefault();
    attempt(() => loadSample(ui.sample.value));
  });
  ui.sample.addEventListener('change', () => state.sampleList.describe());
  ui.file.addEventListener('change', async () => {
    await attempt(() => openFiles(ui.file.files));
    ui.file.value = '';
  });
  for (const box of [ui.plan, ui.labels, ui.path]) box.addEventListener('change', requestRedraw);
  document.addEventListener('keydown', onKey);
  onDroppedFiles(ui.stage, (files) => attempt(() => openFiles(files)));
  new ResizeObserver(() => fit()).observe(ui.stage);
}

/** For tests and the curious: the page's numbers, as last reported by the worker. */
function expose() {
  window.__ksmcmc = {
    snapshot() {
      const s = state.stats;
      const c = s?.chain;
      return {
        ready: state.ready,
        running: state.running,
        name: state.name,
        sample: state.sample,
        generation: s?.generation ?? -1,
        width: s?.width ?? 0,
        height: s?.height ?? 0,
        robot: s?.robot ?? null,
        travelledM: s?.travelledM ?? 0,
        scans: s?.scans ?? 0,
        pathPoints: state.path.length / 2,
        seenFree: s?.seenFree ?? 0,
        truthFree: s?.truthFree ?? 0,
        done: Boolean(s?.done),
        finished: Boolean(s?.finished),
        settled: Boolean(s?.settled),
        renewal: s?.renewal ?? null,
        updates: s?.updates ?? 0,
        lastChanged: s?.lastChanged ?? null,
        chain: Boolean(c),
        iteration: c?.iteration ?? 0,
        units: c?.bestUnits ?? 0,
        k: c?.bestPredictionRate ?? NaN,
        settledAt: c?.settledAt ?? null,
        speed: state.speed,
        updateEveryM: state.updateEveryM,
        scale: state.scale,
        frames: state.frames,
        error: ui.message.hidden ? null : ui.messageText.textContent,
      };
    },
    /** Every hand-over of the robot's map to the chain: { update, travelledM, seenFree, changed, ms }. */
    timeline: () => state.worker.call('timeline'),
    /** The chain's best world as world.json text (null before the chain starts). */
    bestWorldJson: () => state.worker.call('bestWorldJson'),
    heap: () => state.worker.call('heap'),
  };
}

async function main() {
  wire();
  expose();
  if (!(await loadWasm(init))) return;
  ui.version.textContent = version();
  state.worker = new RemoteChain(failed, settled, new URL('./lib/explore-worker.js', import.meta.url));
  const params = new URLSearchParams(location.search);
  if (params.has('seed')) ui.seed.value = params.get('seed');
  if (params.has('speed')) setSpeed(params.get('speed'));
  else setSpeed(ui.speed.value);
  if (params.has('every')) ui.updateEvery.value = params.get('every');
  await attempt(readUpdateEvery);
  ui.file.disabled = false;
  try {
    await state.sampleList.fill(params.get('sample') ?? 'office-small');
    ui.sampleLoad.disabled = false;
  } catch (err) {
    ui.sampleHint.textContent = `The samples did not load (${err.message}): \`make demo\` copies them into www/samples. Open a map file instead.`;
  }
  state.ready = true;
  if (state.sampleList.samples.length > 0) await attempt(() => loadSample(ui.sample.value));
  document.documentElement.dataset.state = 'ready';
  if (params.get('autoplay') === '1') play();
}

main();
