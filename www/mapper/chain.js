// The live mapper's chain, from the page's side: it runs in a Web Worker (lib/chain-worker.js,
// through lib/remote-chain.js), so that no step of it, however long, blocks a frame. Here: the
// chain's settings from the form, starting it on a map, Start/Pause/Step/Reset, what the
// worker says unasked (settled, failed, the wings), and the frame loop: the page draws the
// picture the worker sent, at most one per animation frame, asks for the next one when it has
// drawn the last, and shows the chain's numbers and its trace plots.

import { Map as OccMap } from '../pkg/ksmcmc.js';
import { parseSeed } from '../lib/files.js';
import { cssSize, drawPlot, formatNumber, parseIterationsPerFrame } from '../lib/plot.js';
import { attempt, clearError, say, showError, state, ui } from './state.js';
import { select, syncEdits } from './edits.js';
import { setPainting } from './painting.js';
import { setHover } from './rooms.js';
import { drawBitmap, fit, paintWeak, requestRedraw, showPicture, updateReferenceControls } from './view.js';
import { advanceWeak, startWeak, updateSides } from './weak.js';

/** Step runs this many iterations when the speed is `auto`. */
const AUTO_STEP = 500;

/**
 * The settings text for a new chain: the JSON in the form, with knowledge supervision turned
 * off when its box is unticked. Text that is not a JSON object goes to the chain as it is, so
 * that its own error message names the problem.
 */
function chainSettings() {
  const text = ui.config.value.trim();
  return ui.knowledge.checked ? text : withoutKnowledge(text);
}

/** Settings text with knowledge supervision turned off (text that is not a JSON object: as it is). */
export function withoutKnowledge(text) {
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

/** The seed and settings in the form for a new chain; throws with the reason. */
function chainArgs() {
  const seed = parseSeed(ui.seed.value);
  state.ipf = parseIterationsPerFrame(ui.ipf.value);
  return { config: chainSettings() || undefined, seed, reference: state.referenceJson, knowledge: ui.knowledge.checked };
}

/**
 * Takes on the chain's numbers from a reply, unless a later reply's are already here: the
 * worker numbers them in the order it made them (a picture asked for before a change may
 * arrive after the change's reply).
 */
export function takeStats(stats) {
  if (!state.stats || stats.seq > state.stats.seq) state.stats = stats;
}

/**
 * Takes on a new chain's numbers (the worker has replaced the chain) and starts the statistics
 * afresh; `args` (and `source`, for a new map) are what the chain was started with: the weak
 * prior's chain, if shown, starts over with them.
 */
function adopt({ stats, referenceDropped }, args, source) {
  stopped();
  takeStats(stats);
  if (source) {
    state.source = source;
    state.route?.clear();
  }
  state.args = args;
  state.rooms.restart(stats.generation, stats.iteration);
  startWeak();
  if (referenceDropped) {
    state.referenceJson = null;
    say('The reference world does not fit this map and was dropped.');
  }
  state.trace = { iteration: [], logPosterior: [], acceptance: [] };
  state.initialLogPosterior = stats.logPosterior;
  state.frames = 0;
  state.rate = { iteration: 0, time: performance.now(), perSecond: 0 };
  state.picture?.picture.close();
  state.picture = null;
  state.roomIndex = null;
  setHover(0);
  updateReferenceControls();
  for (const b of [ui.run, ui.step, ui.reset, ui.route.toggle, ui.route.plan, ui.view3d.toggle, ...Object.values(ui.exports)]) b.disabled = false;
  if (source) select(null);
  syncEdits();
  fit();
  requestRedraw();
}

/**
 * Shows a new map and starts a chain on it; `source` says how the worker makes the map. The
 * page's own copy is `map`, or, if null, made from the cells the worker read: the bytes of a
 * file are decoded in the worker only, not a second time on the page's thread. If the map is
 * refused or the chain cannot start, nothing changes (and `map` is freed).
 */
export async function setMap(map, source, { name, label, sample = null, uploaded = false }) {
  let reply;
  let args;
  try {
    args = chainArgs();
    reply = await state.chain.call('load', { source, withCells: !map, ...args });
  } catch (err) {
    map?.free();
    throw err;
  }
  map ??= OccMap.fromCells(reply.cells.width, reply.cells.height, reply.cells.codes);
  const old = state.map;
  state.map = map;
  state.name = name;
  state.label = label;
  state.sample = sample;
  state.base = map.cells();
  state.codes = state.base.slice();
  if (old && old !== map) old.free();
  // A new map: all of it, and none of the old one's pictures.
  state.viewport.view.reset();
  state.viewport.update();
  for (const key of ['shown', 'weakShown']) {
    state[key]?.close();
    state[key] = null;
  }
  ui.mapName.textContent = label ? `· ${label}` : '';
  state.sampleList.show(sample);
  // An opened map is explained until it settles; a sample or a painted map runs on.
  ui.stopSettled.checked = uploaded;
  ui.truth.disabled = !(sample && state.sampleList.samples.find((s) => s.name === sample)?.truth);
  adopt(reply, args, source);
  clearError();
  say(`${label}: ${map.width} × ${map.height} cells. Press Start (or Space).`);
}

export function play() {
  if (!state.stats || state.running) return;
  try {
    state.ipf = parseIterationsPerFrame(ui.ipf.value);
  } catch (err) {
    showError(err);
    return;
  }
  if (state.painting) setPainting(false);
  state.running = true;
  state.rate = { iteration: state.stats.iteration, time: performance.now(), perSecond: state.rate.perSecond };
  ui.run.textContent = 'Pause';
  document.documentElement.dataset.running = 'true';
  say('Running. Space pauses.');
  state.chain.call('play', { ipf: state.ipf, stopWhenSettled: ui.stopSettled.checked }).catch(showError);
  requestRedraw();
}

/** The page's side of stopping: the buttons and the flag. */
function stopped() {
  state.running = false;
  ui.run.textContent = 'Start';
  document.documentElement.dataset.running = 'false';
}

export function pause() {
  if (!state.running) return;
  state.running = false;
  ui.run.textContent = 'Start';
  const generation = state.stats.generation;
  state.chain.call('pause').then((stats) => {
    // Marked paused once the worker has stopped, with its last numbers drawn.
    if (state.running || stats.generation !== generation) return;
    takeStats(stats);
    document.documentElement.dataset.running = 'false';
    say(`Paused at iteration ${formatNumber(stats.iteration)}.`);
    requestRedraw();
  }, showError);
}

export function toggle() {
  if (state.running) pause();
  else play();
}

/** The worker paused the chain because it settled. */
export function chainSettled(stats) {
  takeStats(stats);
  stopped();
  say(
    `Settled at iteration ${formatNumber(stats.settledAt)}: the best log posterior improved by less than 0.3 % ` +
      `over the last ${formatNumber(stats.settleWindow)} iterations. Start runs on.`,
  );
  requestRedraw();
}

/**
 * The worker explains the wings of a building whose walls follow several directions, a chain
 * per wing once the chain has stopped (`stats.wings`), or has explained them (`wingsDone`):
 * the best world's rooms and picture are then theirs.
 */
export function chainWings(stats) {
  takeStats(stats);
  const w = stats.wings;
  if (w) {
    const side = w.running > 1 ? `, ${w.running} wings side by side` : '';
    say(
      `The walls follow ${w.of} directions: explaining wing ${w.wing} of ${w.of} in its own direction ` +
        `(${formatNumber(w.rotationDeg, 1)}°), ${formatNumber(w.target)} iterations as the first chain ran${side}.`,
    );
  } else if (stats.wingsDone > 0) {
    say(`The ${stats.wingsDone} wings were explained each in its own direction: the best world's units lie at their angles.`);
    state.rooms.request();
    requestRedraw();
  }
}

/** The worker stopped the chain because a step failed. */
export function chainFailed(message, stats) {
  if (stats) takeStats(stats);
  stopped();
  showError(new Error(message));
  requestRedraw();
}

/** What the worker draws: the view and the pixel sizes of the two canvases. */
function view() {
  const s = state.stats;
  const dpr = globalThis.devicePixelRatio || 1;
  const gw = Math.max(80, Math.round(cssSize(ui.graph).width * dpr) || 320);
  const gh = Math.max(60, Math.round(gw * Math.min(1, Math.max(0.45, s.height / s.width))));
  return {
    generation: s.generation,
    show: state.show,
    cloud: state.cloud,
    labels: state.labels,
    unitLabels: state.unitLabels,
    // The legend is the page's, beside the map, where it stays readable (issue 33).
    legend: false,
    scale: state.drawScale,
    graphWidth: gw,
    graphHeight: gh,
    graphShow: state.show === 'none' ? 'best' : state.show,
    traceFrom: state.trace.iteration.length,
  };
}

/** Asks the worker for a picture, unless one is on its way. */
function requestPicture() {
  if (state.inFlight || !state.stats) return;
  state.inFlight = true;
  state.redrawPending = false;
  const asked = view();
  state.chain.call('frame', asked).then(
    (result) => {
      state.inFlight = false;
      if (!result || result.stats.generation !== state.stats.generation) {
        result?.picture.close();
        result?.graph.close();
        if (state.running || state.redrawPending) schedule();
        return;
      }
      state.picture?.picture.close();
      state.picture?.graph.close();
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

export function schedule() {
  if (!state.raf) state.raf = requestAnimationFrame(frame);
}

/**
 * One animation frame: draws the picture the worker sent, if one came, and asks for the next
 * one while the chain runs (or the view changed). Nothing here waits for the chain.
 */
function frame() {
  state.raf = 0;
  if (state.picture) {
    const t0 = performance.now();
    draw(state.picture);
    state.picture = null;
    state.drawMs = 0.8 * state.drawMs + 0.2 * (performance.now() - t0);
  }
  if (state.running || state.redrawPending) requestPicture();
  const now = performance.now();
  state.rooms.follow(state.stats, state.running, now);
  const weak = state.weak;
  if (weak) {
    if (weak.picture) {
      state.weakShown?.close();
      state.weakShown = weak.picture;
      weak.picture = null;
      paintWeak();
      updateSides();
    }
    const caughtUp = weak.stats && state.stats && weak.stats.iteration === state.stats.iteration;
    weak.rooms.follow(weak.stats, !caughtUp || state.running, now);
    advanceWeak();
  }
}

export function step() {
  if (!state.stats) return;
  attempt(async () => {
    state.ipf = parseIterationsPerFrame(ui.ipf.value);
    const n = state.ipf === 'auto' ? AUTO_STEP : state.ipf;
    takeStats(await state.chain.call('step', { n }));
    say(`Ran ${formatNumber(n)} iterations.`);
    requestRedraw();
  });
}

/** Starts the chain over on the same map, with the seed and settings now in the form. */
export function reset() {
  if (!state.map) return;
  attempt(async () => {
    const wasRunning = state.running;
    const args = chainArgs();
    adopt(await state.chain.call('start', args), args);
    clearError();
    say(`Started over with seed ${ui.seed.value.trim()}.`);
    if (wasRunning) play();
  });
}

function draw({ stats, trace, picture, graph }) {
  takeStats(stats);
  showPicture(picture);
  drawBitmap(ui.graph, graph);
  if (stats.running) state.frames++;
  const now = performance.now();
  if (now - state.rate.time >= 500) {
    state.rate = { iteration: stats.iteration, time: now, perSecond: ((stats.iteration - state.rate.iteration) * 1000) / (now - state.rate.time) };
  }
  if (trace) {
    const t = state.trace;
    t.iteration.push(...trace.iteration);
    t.logPosterior.push(...trace.logPosterior);
    t.acceptance.push(...trace.acceptance);
  }
  updateTrace();
  updateStats();
  updateSides();
}

function updateTrace() {
  const t = state.trace;
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
  const m = state.stats;
  const s = ui.stat;
  s.iteration.textContent = formatNumber(m.iteration);
  s.rate.textContent = state.running ? formatNumber(state.rate.perSecond) : '–';
  s.lp.textContent = formatNumber(m.logPosterior, 1);
  s.best.textContent = formatNumber(m.bestLogPosterior, 1);
  s.acc.textContent = `${formatNumber(100 * m.acceptance, 1)} %`;
  // Once a building's wings are explained, the best world is theirs (a chain per wing).
  const wings = m.wingsDone > 0 ? ` (${m.wingsUnits} in ${m.wingsDone} wings)` : '';
  s.units.textContent = `${m.units} now, ${m.bestUnits} best${wings}`;
  s.doors.textContent = `${m.doors} now, ${m.bestDoors} best`;
  s.k.textContent = m.wingsDone > 0
    ? `${formatNumber(m.wingsPredictionRate, 4)} in ${m.wingsDone} wings (${formatNumber(m.bestPredictionRate, 4)} one chain)`
    : formatNumber(m.bestPredictionRate, 4);
  s.rotation.textContent = `${formatNumber(m.rotationDeg, 1)}°`;
  s.setup.textContent = `${formatNumber(m.setupMs)} ms`;
  s.settled.textContent = m.settledAt !== null
    ? `at iteration ${formatNumber(m.settledAt)}`
    : `not yet (last improvement at ${formatNumber(m.improvedAt ?? 0)}, window ${formatNumber(m.settleWindow)})`;
  const d = ui.stats.dataset;
  d.iteration = String(m.iteration);
  d.logPosterior = String(m.logPosterior);
  d.bestLogPosterior = String(m.bestLogPosterior);
  d.units = String(m.units);
  d.bestUnits = String(m.bestUnits);
  ui.canvas.setAttribute(
    'aria-label',
    `${state.label || 'Map'}, ${m.width} by ${m.height} cells, with the ${state.show === 'none' ? 'map only' : `${state.show} world`}: ` +
      `${m.bestUnits} units in the best world after ${formatNumber(m.iteration)} iterations`,
  );
}

/** Calls one of the chain's export methods in the worker. */
export function invoke(name, ...args) {
  return state.chain.call('invoke', { name, args });
}
