// The live mapper page: a data-driven MCMC chain explains an occupancy map with a semantic
// floor plan while you watch. The chain, the pictures and the exports are the library's
// (pkg/ksmcmc.js); this file is wiring: a requestAnimationFrame loop that gives the chain a
// time budget (or a number of iterations) per frame and redraws at most once per frame.

import init, {
  Map as OccMap, Mapper, chainConfigDefaults, drawMapper, drawSceneGraph, drawToCanvas, version,
} from './pkg/ksmcmc.js';
import { TOOLS, MAX_BRUSH, brushOffsets, stamp, strokeTo, cellAt } from './lib/paint.js';
import { planOpen, pickYamlImage, stem, parseSeed, onDroppedFiles } from './lib/files.js';
import { drawPlot, formatNumber, parseIterationsPerFrame } from './lib/plot.js';
import { messages } from './lib/messages.js';
import { download } from './lib/download.js';

/**
 * Milliseconds per animation frame for iterating and drawing together in `auto` mode: the
 * chain gets what drawing leaves of it (at least MIN_BUDGET_MS), so frames keep to 60 Hz.
 */
const FRAME_MS = 14;
const MIN_BUDGET_MS = 4;
/** Step runs this many iterations when the speed is `auto`. */
const AUTO_STEP = 500;
/** The most pixels per cell the page draws (more only costs time per frame). */
const MAX_SCALE = 3;

const $ = (id) => document.getElementById(id);
const ui = {
  message: $('message'), messageText: $('message-text'), messageClose: $('message-close'),
  status: $('status'), version: $('version'),
  run: $('run'), step: $('step'), reset: $('reset'), seed: $('seed'), ipf: $('ipf'),
  config: $('config'), configDefaults: $('config-defaults'), knowledge: $('knowledge'),
  sampleForm: $('sample-form'), sample: $('sample'), sampleLoad: $('sample-load'), sampleHint: $('sample-hint'),
  file: $('file'), classify: $('classify'),
  paint: $('paint'), brush: $('brush'), brushValue: $('brush-value'),
  blankForm: $('blank-form'), blankWidth: $('blank-width'), blankHeight: $('blank-height'), blankCreate: $('blank-create'),
  showReference: $('show-reference'), cloud: $('cloud'), labels: $('labels'),
  worldFile: $('world-file'), truth: $('truth'), referenceClear: $('reference-clear'),
  stage: $('stage'), canvas: $('map'), graph: $('graph'), mapName: $('map-name'),
  plotLp: $('plot-lp'), plotAcc: $('plot-acc'), plotLpValue: $('plot-lp-value'), plotAccValue: $('plot-acc-value'),
  stats: $('stats'),
  stat: {
    iteration: $('stat-iteration'), rate: $('stat-rate'), lp: $('stat-lp'), best: $('stat-best'), acc: $('stat-acc'),
    units: $('stat-units'), doors: $('stat-doors'), k: $('stat-k'), rotation: $('stat-rotation'), setup: $('stat-setup'),
  },
  exports: {
    world: $('export-world'), labels: $('export-labels'), png: $('export-png'), graph: $('export-graph'),
    report: $('export-report'),
  },
};

const { showError, clearError, say, attempt, loadWasm } = messages(ui);

const state = {
  ready: false,
  /** The map being explained (a wasm Map, owned here) and what it is. */
  map: null,
  name: 'map',
  label: '',
  sample: null,
  samples: [],
  /** The chain (a wasm Mapper), or null before the first map. */
  mapper: null,
  running: false,
  raf: 0,
  redrawPending: false,
  ipf: 'auto',
  show: 'current',
  cloud: false,
  labels: true,
  /** The reference world's text, kept to re-apply when the chain is rebuilt. */
  referenceJson: null,
  referenceName: '',
  /** The trace as read so far (plain arrays, appended to each frame). */
  trace: { iteration: [], logPosterior: [], acceptance: [] },
  initialLogPosterior: NaN,
  /** Frames in which the chain advanced, and when it last started: for iterations/s. */
  frames: 0,
  rate: { iteration: 0, time: 0, perSecond: 0 },
  /** Milliseconds a redraw takes (a running average). */
  drawMs: 4,
  scale: 1,
  /** Painting: cell codes as loaded and as painted, the stroke's last cell. */
  painting: false,
  tool: 'occupied',
  brush: 3,
  offsets: brushOffsets(3),
  base: null,
  codes: null,
  strokeAt: null,
  strokeUndo: null,
};

// ---------------------------------------------------------------- the chain

/**
 * The settings text for a new chain: the JSON in the form, with knowledge supervision turned
 * off when its box is unticked. Text that is not a JSON object goes to the chain as it is, so
 * that its own error message names the problem.
 */
function chainSettings() {
  const text = ui.config.value.trim();
  if (ui.knowledge.checked) return text;
  let settings = {};
  if (text) {
    try {
      settings = JSON.parse(text);
    } catch {
      return text;
    }
  }
  if (settings === null || typeof settings !== 'object' || Array.isArray(settings)) return text;
  const knowledge = typeof settings.knowledge === 'object' && settings.knowledge !== null ? settings.knowledge : {};
  return JSON.stringify({ ...settings, knowledge: { ...knowledge, enabled: false } });
}

/** A new chain on `map` with the seed and settings in the form; throws with the reason. */
function newMapper(map) {
  const seed = parseSeed(ui.seed.value);
  state.ipf = parseIterationsPerFrame(ui.ipf.value);
  const mapper = new Mapper(map, chainSettings(), seed);
  if (state.referenceJson !== null) {
    try {
      mapper.setReference(state.referenceJson);
    } catch {
      state.referenceJson = null;
      say('The reference world does not fit this map and was dropped.');
    }
  }
  return mapper;
}

/** Replaces the chain (freeing the old one) and starts the statistics afresh. */
function adopt(mapper) {
  const wasRunning = state.running;
  pause();
  state.mapper?.free();
  state.mapper = mapper;
  state.trace = { iteration: [], logPosterior: [], acceptance: [] };
  state.initialLogPosterior = mapper.logPosterior;
  state.frames = 0;
  state.rate = { iteration: 0, time: performance.now(), perSecond: 0 };
  updateReferenceControls();
  for (const b of [ui.run, ui.step, ui.reset, ...Object.values(ui.exports)]) b.disabled = false;
  fit();
  requestRedraw();
  return wasRunning;
}

/** Shows a new map and starts a chain on it. If the chain cannot start, nothing changes. */
function setMap(map, { name, label, sample = null }) {
  let mapper;
  try {
    mapper = newMapper(map);
  } catch (err) {
    map.free();
    throw err;
  }
  const old = state.map;
  state.map = map;
  state.name = name;
  state.label = label;
  state.sample = sample;
  state.base = map.cells();
  state.codes = state.base.slice();
  if (old && old !== map) old.free();
  ui.mapName.textContent = label ? `· ${label}` : '';
  ui.truth.disabled = !(sample && state.samples.find((s) => s.name === sample)?.truth);
  adopt(mapper);
  clearError();
  say(`${label}: ${map.width} × ${map.height} cells. ${state.running ? '' : 'Press Start (or Space).'}`);
}

function play() {
  if (!state.mapper || state.running) return;
  try {
    state.ipf = parseIterationsPerFrame(ui.ipf.value);
  } catch (err) {
    showError(err);
    return;
  }
  if (state.painting) setPainting(false);
  state.running = true;
  state.rate = { iteration: state.mapper.iteration, time: performance.now(), perSecond: state.rate.perSecond };
  ui.run.textContent = 'Pause';
  document.documentElement.dataset.running = 'true';
  if (!state.raf) state.raf = requestAnimationFrame(frame);
}

function pause() {
  if (!state.running) return;
  state.running = false;
  ui.run.textContent = 'Start';
  document.documentElement.dataset.running = 'false';
  requestRedraw();
}

function toggle() {
  if (state.running) pause();
  else play();
}

/**
 * One animation frame: advance the chain, then draw. Drawing a large map takes longer than a
 * frame can spare, so it is spread out: with a redraw of `drawMs`, only every
 * ceil(drawMs / 7)-th frame draws, and the other frames give the chain the whole budget.
 */
function frame() {
  state.raf = 0;
  if (!state.running || !state.mapper) {
    if (state.redrawPending) redraw();
    return;
  }
  const every = Math.max(1, Math.ceil(state.drawMs / (FRAME_MS / 2)));
  const draws = state.frames % every === 0;
  try {
    if (state.ipf !== 'auto') state.mapper.step(state.ipf);
    else state.mapper.runFor(draws ? Math.max(MIN_BUDGET_MS, FRAME_MS - state.drawMs) : FRAME_MS - 2);
  } catch (err) {
    pause();
    showError(err);
    return;
  }
  state.frames++;
  const now = performance.now();
  if (now - state.rate.time >= 500) {
    const it = state.mapper.iteration;
    state.rate = { iteration: it, time: now, perSecond: ((it - state.rate.iteration) * 1000) / (now - state.rate.time) };
  }
  if (draws) {
    const t0 = performance.now();
    redraw();
    state.drawMs = 0.8 * state.drawMs + 0.2 * (performance.now() - t0);
  }
  state.raf = requestAnimationFrame(frame);
}

function step() {
  if (!state.mapper) return;
  attempt(() => {
    state.ipf = parseIterationsPerFrame(ui.ipf.value);
    const n = state.ipf === 'auto' ? AUTO_STEP : state.ipf;
    state.mapper.step(n);
    say(`Ran ${formatNumber(n)} iterations.`);
    requestRedraw();
  });
}

/** Starts the chain over on the same map, with the seed and settings now in the form. */
function reset() {
  if (!state.map) return;
  attempt(() => {
    const wasRunning = adopt(newMapper(state.map));
    clearError();
    say(`Started over with seed ${ui.seed.value.trim()}.`);
    if (wasRunning) play();
  });
}

// ---------------------------------------------------------------- drawing

/** Redraws at the next animation frame (once, however often it is asked). */
function requestRedraw() {
  state.redrawPending = true;
  if (!state.raf) state.raf = requestAnimationFrame(frame);
}

function redraw() {
  state.redrawPending = false;
  const m = state.mapper;
  if (!m) return;
  try {
    drawMapper(ui.canvas, m, { show: state.show, cloud: state.cloud, labels: state.labels, scale: state.scale });
    const dpr = globalThis.devicePixelRatio || 1;
    const gw = Math.max(80, Math.round(ui.graph.clientWidth * dpr) || 320);
    const gh = Math.max(60, Math.round(gw * Math.min(1, Math.max(0.45, m.height / m.width))));
    drawSceneGraph(ui.graph, m, { show: state.show === 'none' ? 'best' : state.show, width: gw, height: gh });
  } catch (err) {
    pause();
    showError(err);
    return;
  }
  updateTrace();
  updateStats();
}

function updateTrace() {
  const m = state.mapper;
  const t = state.trace;
  if (m.traceLength > t.iteration.length) {
    const more = m.trace(t.iteration.length);
    t.iteration.push(...more.iteration);
    t.logPosterior.push(...more.logPosterior);
    t.acceptance.push(...more.acceptance);
  }
  const dark = matchMedia('(prefers-color-scheme: dark)').matches;
  drawPlot(ui.plotLp, t.iteration, t.logPosterior, { color: dark ? '#6ea8ff' : '#1f5fbf' });
  drawPlot(ui.plotAcc, t.iteration, t.acceptance, { color: dark ? '#f0a500' : '#b35900', range: [0, 1] });
  const last = t.iteration.length - 1;
  ui.plotLpValue.textContent = last >= 0 ? formatNumber(t.logPosterior[last]) : '';
  ui.plotAccValue.textContent = last >= 0 ? `${formatNumber(100 * t.acceptance[last], 1)} %` : '';
  ui.plotLp.setAttribute('aria-label', last >= 0
    ? `Log posterior over ${formatNumber(t.iteration[last])} iterations: from ${formatNumber(t.logPosterior[0])} to ${formatNumber(t.logPosterior[last])}`
    : 'Log posterior: no iterations yet');
  ui.plotAcc.setAttribute('aria-label', last >= 0
    ? `Acceptance rate, now ${formatNumber(100 * t.acceptance[last], 1)} %`
    : 'Acceptance rate: no iterations yet');
}

function updateStats() {
  const m = state.mapper;
  const s = ui.stat;
  const bestUnits = m.bestUnits;
  s.iteration.textContent = formatNumber(m.iteration);
  s.rate.textContent = state.running ? formatNumber(state.rate.perSecond) : '–';
  s.lp.textContent = formatNumber(m.logPosterior, 1);
  s.best.textContent = formatNumber(m.bestLogPosterior, 1);
  s.acc.textContent = `${formatNumber(100 * m.acceptance, 1)} %`;
  s.units.textContent = `${m.units} (${bestUnits})`;
  s.doors.textContent = `${m.doors} (${m.bestDoors})`;
  s.k.textContent = formatNumber(m.bestPredictionRate, 4);
  s.rotation.textContent = `${formatNumber(m.rotationDeg, 1)}°`;
  s.setup.textContent = `${formatNumber(m.setupMs)} ms`;
  const d = ui.stats.dataset;
  d.iteration = String(m.iteration);
  d.logPosterior = String(m.logPosterior);
  d.bestLogPosterior = String(m.bestLogPosterior);
  d.units = String(m.units);
  d.bestUnits = String(bestUnits);
  ui.canvas.setAttribute(
    'aria-label',
    `${state.label || 'Map'}, ${m.width} by ${m.height} cells, with the ${state.show === 'none' ? 'map only' : `${state.show} world`}: ` +
      `${bestUnits} units in the best world after ${formatNumber(m.iteration)} iterations`,
  );
}

/**
 * Sizes the canvas on screen to fit the stage, and picks the drawing scale: enough pixels per
 * cell for the screen's resolution (at most 3), so that the picture is shrunk smoothly rather
 * than blown up, except for small maps on large screens.
 */
function fit() {
  const m = state.mapper ?? state.map;
  if (!m) return;
  const box = ui.stage.getBoundingClientRect();
  const availW = Math.max(64, box.width - 16);
  const availH = Math.max(200, Math.min(window.innerHeight * 0.7, 1200));
  const s = Math.min(availW / m.width, availH / m.height);
  ui.canvas.style.width = `${Math.max(1, Math.round(m.width * s))}px`;
  ui.canvas.style.height = `${Math.max(1, Math.round(m.height * s))}px`;
  const dpr = globalThis.devicePixelRatio || 1;
  state.scale = Math.min(MAX_SCALE, Math.max(1, Math.ceil(s * dpr - 0.01)));
  // Shrinking with nearest-neighbour drops thin lines: smooth it; enlarging stays crisp.
  ui.canvas.classList.toggle('smooth', state.scale >= s * dpr);
  requestRedraw();
}

// ---------------------------------------------------------------- maps

async function loadSample(name) {
  const info = state.samples.find((s) => s.name === name);
  if (!info) throw new Error(`There is no sample "${name}".`);
  const get = async (file) => {
    const r = await fetch(`samples/${name}/${file}`);
    if (!r.ok) throw new Error(`samples/${name}/${file}: ${r.status} ${r.statusText}`);
    return r;
  };
  const [yaml, pgm] = await Promise.all([get('map.yaml').then((r) => r.text()), get('map.pgm').then((r) => r.arrayBuffer())]);
  const map = OccMap.fromYaml(yaml, new Uint8Array(pgm));
  ui.sample.value = name;
  setMap(map, { name, label: name, sample: name });
}

/** Loads a map from the picked files: one image, or a map.yaml with the image it names. */
async function openFiles(fileList) {
  const files = [...fileList];
  const plan = planOpen(files.map((f) => f.name));
  if (plan.kind === 'error') throw new Error(plan.message);
  const byName = (n) => files.find((f) => f.name === n);
  if (plan.kind === 'image') {
    const file = byName(plan.image);
    let map = OccMap.fromBytes(new Uint8Array(await file.arrayBuffer()));
    if (ui.classify.value === 'auto') {
      const auto = map.reclassify('auto');
      map.free();
      map = auto;
    }
    setMap(map, { name: stem(file.name), label: file.name });
    return;
  }
  const yamlText = await byName(plan.yaml).text();
  const pick = pickYamlImage(plan.yaml, yamlText, plan.images);
  if ('message' in pick) throw new Error(pick.message);
  const image = new Uint8Array(await byName(pick.image).arrayBuffer());
  setMap(OccMap.fromYaml(yamlText, image), { name: stem(plan.yaml), label: `${plan.yaml} + ${pick.image}` });
}

/** A blank map to paint on: one free room inside a two-cell wall, which the chain explains at once. */
function blankMap() {
  const read = (input, what) => {
    const v = Number(input.value);
    if (!Number.isInteger(v) || v < 12 || v > 2000) throw new Error(`${what} must be a whole number from 12 to 2000 cells.`);
    return v;
  };
  const w = read(ui.blankWidth, 'Width');
  const h = read(ui.blankHeight, 'Height');
  const codes = new Uint8Array(w * h);
  for (let y = 0; y < h; y++) {
    for (let x = 0; x < w; x++) {
      if (x < 2 || y < 2 || x >= w - 2 || y >= h - 2) codes[y * w + x] = 2;
    }
  }
  setMap(OccMap.fromCells(w, h, codes), { name: 'painted', label: `blank ${w} × ${h}` });
  setPainting(true);
  ui.stage.scrollIntoView({ block: 'nearest' });
  say(`New ${w} × ${h} map: paint walls into it, then press Start.`);
}

// ---------------------------------------------------------------- painting

function setPainting(on) {
  state.painting = on;
  ui.paint.checked = on;
  ui.canvas.classList.toggle('painting', on);
  if (on) {
    pause();
    say('Painting: drag on the map. Each stroke starts the chain over on the painted map.');
  }
}

function cellFromEvent(e) {
  const r = ui.canvas.getBoundingClientRect();
  return cellAt(e.clientX - r.left, e.clientY - r.top, r, state.map.width, state.map.height);
}

/** Shows the painted cells (without a world) while a stroke goes on. */
function showPainted() {
  attempt(() => {
    const painted = OccMap.fromCells(state.map.width, state.map.height, state.codes);
    try {
      drawToCanvas(ui.canvas, painted, undefined, state.scale, false);
    } finally {
      painted.free();
    }
  });
}

let paintFramePending = false;
function schedulePaint() {
  if (paintFramePending) return;
  paintFramePending = true;
  requestAnimationFrame(() => {
    paintFramePending = false;
    showPainted();
  });
}

function onPointerDown(e) {
  if (!state.painting || !state.map || (e.pointerType === 'mouse' && e.button !== 0)) return;
  e.preventDefault();
  ui.canvas.setPointerCapture?.(e.pointerId);
  state.strokeUndo = state.codes.slice();
  state.strokeAt = cellFromEvent(e);
  const [x, y] = state.strokeAt;
  if (stamp(state.codes, state.base, state.map.width, state.map.height, x, y, state.offsets, TOOLS[state.tool])) schedulePaint();
}

function onPointerMove(e) {
  if (!state.strokeAt) return;
  const cell = cellFromEvent(e);
  const { width, height } = state.map;
  if (strokeTo(state.codes, state.base, width, height, state.strokeAt, cell, state.offsets, TOOLS[state.tool])) schedulePaint();
  state.strokeAt = cell;
}

/** The stroke is done: the painted map replaces the map, and the chain starts over on it. */
function onPointerUp() {
  if (!state.strokeAt) return;
  state.strokeAt = null;
  const { width, height } = state.map;
  try {
    const painted = OccMap.fromCells(width, height, state.codes);
    let mapper;
    try {
      mapper = newMapper(painted);
    } catch (err) {
      painted.free();
      throw err;
    }
    state.map.free();
    state.map = painted;
    adopt(mapper);
    clearError();
    say('Painted. Press Start to explain the painted map.');
  } catch (err) {
    state.codes = state.strokeUndo ?? state.base.slice();
    showError(new Error(`${err instanceof Error ? err.message : err} (the stroke was undone)`));
    requestRedraw();
  }
}

function setBrush(size) {
  const s = Math.min(MAX_BRUSH, Math.max(1, Math.round(Number(size)) || 1));
  state.brush = s;
  state.offsets = brushOffsets(s);
  ui.brush.value = String(s);
  ui.brushValue.textContent = String(s);
}

// ---------------------------------------------------------------- view and reference

function setShow(show) {
  if (show === 'reference' && !state.mapper?.hasReference) return;
  state.show = show;
  const radio = document.querySelector(`input[name="show"][value="${show}"]`);
  if (radio) radio.checked = true;
  requestRedraw();
}

function setCloud(on) {
  state.cloud = on;
  ui.cloud.checked = on;
  requestRedraw();
}

function setLabels(on) {
  state.labels = on;
  ui.labels.checked = on;
  requestRedraw();
}

function updateReferenceControls() {
  const has = Boolean(state.mapper?.hasReference);
  ui.showReference.disabled = !has;
  ui.referenceClear.disabled = !has;
  if (!has && state.show === 'reference') setShow('best');
}

function setReference(text, name) {
  state.mapper.setReference(text);
  state.referenceJson = text;
  state.referenceName = name;
  updateReferenceControls();
  setShow('reference');
  clearError();
  say(`Showing ${name} as the reference world.`);
}

// ---------------------------------------------------------------- exports

function save(name, data, type) {
  download(name, data, type);
  say(`Saved ${name}.`);
}

// ---------------------------------------------------------------- keyboard

function onKey(e) {
  if (e.ctrlKey || e.metaKey || e.altKey || e.defaultPrevented) return;
  const t = e.target;
  if (t.closest?.('input, textarea, select, [contenteditable]')) return;
  const key = e.key.toLowerCase();
  // Space on a focused button presses that button; elsewhere it starts and pauses.
  if (key === ' ' && t.closest?.('button, a, summary')) return;
  const actions = {
    ' ': toggle,
    s: step,
    r: reset,
    c: () => setShow('current'),
    b: () => setShow('best'),
    t: () => setShow('reference'),
    u: () => setCloud(!state.cloud),
    l: () => setLabels(!state.labels),
    p: () => setPainting(!state.painting),
  };
  const action = actions[key];
  if (!action || !state.ready) return;
  e.preventDefault();
  action();
}

// ---------------------------------------------------------------- wiring

function wire() {
  ui.messageClose.addEventListener('click', clearError);
  ui.run.addEventListener('click', toggle);
  ui.step.addEventListener('click', step);
  ui.reset.addEventListener('click', reset);
  // Checked when it changes; an error stays until the next action succeeds (clearing it here,
  // on blur, would move the page under the pointer that is about to click).
  ui.ipf.addEventListener('change', () =>
    attempt(() => {
      state.ipf = parseIterationsPerFrame(ui.ipf.value);
    }),
  );
  ui.configDefaults.addEventListener('click', () => {
    ui.config.value = chainConfigDefaults();
  });
  ui.sampleForm.addEventListener('submit', (e) => {
    e.preventDefault();
    attempt(() => loadSample(ui.sample.value));
  });
  ui.file.addEventListener('change', async () => {
    await attempt(() => openFiles(ui.file.files));
    ui.file.value = '';
  });
  ui.paint.addEventListener('change', () => setPainting(ui.paint.checked));
  for (const radio of document.querySelectorAll('input[name="tool"]')) {
    radio.addEventListener('change', () => {
      state.tool = radio.value;
    });
  }
  ui.brush.addEventListener('input', () => setBrush(ui.brush.value));
  ui.blankForm.addEventListener('submit', (e) => {
    e.preventDefault();
    attempt(blankMap);
  });
  for (const radio of document.querySelectorAll('input[name="show"]')) {
    radio.addEventListener('change', () => setShow(radio.value));
  }
  ui.cloud.addEventListener('change', () => setCloud(ui.cloud.checked));
  ui.labels.addEventListener('change', () => setLabels(ui.labels.checked));
  ui.worldFile.addEventListener('change', async () => {
    const file = ui.worldFile.files[0];
    if (file) await attempt(async () => setReference(await file.text(), file.name));
    ui.worldFile.value = '';
  });
  ui.truth.addEventListener('click', () =>
    attempt(async () => {
      const r = await fetch(`samples/${state.sample}/truth.json`);
      if (!r.ok) throw new Error(`samples/${state.sample}/truth.json: ${r.status} ${r.statusText}`);
      setReference(await r.text(), `${state.sample}/truth.json`);
    }),
  );
  ui.referenceClear.addEventListener('click', () => {
    state.mapper?.setReference();
    state.referenceJson = null;
    updateReferenceControls();
    say('Reference cleared.');
    requestRedraw();
  });

  const ex = ui.exports;
  ex.world.addEventListener('click', () => attempt(() => save('world.json', state.mapper.bestWorldJson(), 'application/json')));
  ex.labels.addEventListener('click', () => attempt(() => save('labels.pgm', state.mapper.labelsPgm(), 'image/x-portable-graymap')));
  ex.png.addEventListener('click', () =>
    attempt(() => save('overlay.png', state.mapper.toPng({ show: state.show, cloud: state.cloud, labels: state.labels }), 'image/png')),
  );
  ex.graph.addEventListener('click', () => attempt(() => save('graph.json', state.mapper.graphJson(), 'application/json')));
  ex.report.addEventListener('click', () => attempt(() => save('report.json', state.mapper.reportJson(), 'application/json')));

  ui.canvas.addEventListener('pointerdown', onPointerDown);
  ui.canvas.addEventListener('pointermove', onPointerMove);
  ui.canvas.addEventListener('pointerup', onPointerUp);
  ui.canvas.addEventListener('pointercancel', onPointerUp);
  document.addEventListener('keydown', onKey);

  onDroppedFiles(ui.stage, (files) => attempt(() => openFiles(files)));
  new ResizeObserver(() => fit()).observe(ui.stage);
  window.addEventListener('resize', fit);
}

/** For tests and the curious: the page's numbers, read from the running chain. */
function expose() {
  window.__ksmcmc = {
    get mapper() {
      return state.mapper;
    },
    snapshot() {
      const m = state.mapper;
      return {
        ready: state.ready,
        running: state.running,
        name: state.name,
        sample: state.sample,
        width: m?.width ?? 0,
        height: m?.height ?? 0,
        seed: m ? String(m.seed) : null,
        iteration: m?.iteration ?? 0,
        logPosterior: m?.logPosterior ?? NaN,
        bestLogPosterior: m?.bestLogPosterior ?? NaN,
        initialLogPosterior: state.initialLogPosterior,
        units: m?.units ?? 0,
        bestUnits: m?.bestUnits ?? 0,
        acceptance: m?.acceptance ?? NaN,
        frames: state.frames,
        traceLength: state.trace.iteration.length,
        hasReference: Boolean(m?.hasReference),
        show: state.show,
        cloud: state.cloud,
        scale: state.scale,
        ipf: state.ipf,
        drawMs: state.drawMs,
        painting: state.painting,
        error: ui.message.hidden ? null : ui.messageText.textContent,
      };
    },
  };
}

async function main() {
  wire();
  expose();
  if (!(await loadWasm(init))) return;
  ui.version.textContent = version();
  setBrush(ui.brush.value);
  for (const el of [ui.file, ui.blankCreate, ui.worldFile]) el.disabled = false;

  const params = new URLSearchParams(location.search);
  if (params.has('seed')) ui.seed.value = params.get('seed');
  if (params.has('ipf')) ui.ipf.value = params.get('ipf');
  try {
    const r = await fetch('samples/index.json');
    if (!r.ok) throw new Error(`${r.status} ${r.statusText}`);
    state.samples = await r.json();
    for (const s of state.samples) {
      ui.sample.append(new Option(`${s.name} (${s.width} × ${s.height})`, s.name));
    }
    ui.sample.disabled = ui.sampleLoad.disabled = false;
    const describe = () => {
      ui.sampleHint.textContent = state.samples.find((s) => s.name === ui.sample.value)?.description ?? '';
    };
    ui.sample.addEventListener('change', describe);
    const wanted = params.get('sample') ?? 'office-small';
    ui.sample.value = state.samples.some((s) => s.name === wanted) ? wanted : state.samples[0]?.name;
    describe();
  } catch (err) {
    ui.sampleHint.textContent = `The samples did not load (${err.message}): \`make demo\` copies them into www/samples. Open or paint a map instead.`;
  }
  state.ready = true;
  const first = state.samples.length > 0 ? attempt(() => loadSample(ui.sample.value)) : attempt(blankMap);
  await first;
  if (!state.mapper) await attempt(blankMap);
  document.documentElement.dataset.state = 'ready';
  if (params.get('autoplay') === '1') play();
}

main();
