// The table-top page: a knowledge-supervised MCMC chain over noisy 6D box poses builds a
// scene graph while you watch. The chain, the analysis and the pictures are the library's
// (pkg/ksmcmc_tabletop.js); this file is wiring: a requestAnimationFrame loop that gives the chain a
// time budget per frame and redraws the view, the graph and the probability table. Both
// pictures zoom and pan (lib/viewport.js): the library draws them off screen, and they are
// shown through their views.

import init, { Tabletop, tabletopSynth, tabletopRulesDefault, tabletopCheckRules, version, wasmHeapBytes } from './pkg/ksmcmc_tabletop.js';
import { messages } from './lib/messages.js';
import { download } from './lib/download.js';
import { rulesEditor } from './lib/rules-editor.js';
import { Viewport } from './lib/viewport.js';

/** Milliseconds of iterations per animation frame. */
const BUDGET_MS = 10;
/** Width of the camera view at zoom 1, pixels; zoomed in, it is drawn twice as wide. */
const VIEW_WIDTH = 800;

const $ = (id) => document.getElementById(id);
const ui = {
  message: $('message'), messageText: $('message-text'), messageClose: $('message-close'),
  run: $('run'), step: $('step'), reset: $('reset'), seed: $('seed'),
  synthForm: $('synth-form'), synthSeed: $('synth-seed'), synthObjects: $('synth-objects'), generate: $('generate'),
  file: $('file'), download: $('download'),
  rules: $('rules'), rulesError: $('rules-error'), rulesApply: $('rules-apply'), rulesDefault: $('rules-default'),
  view: $('view'), graph: $('graph'), tbody: document.querySelector('#probs tbody'), sceneName: $('scene-name'),
  status: $('status'), version: $('version'),
  stat: { iteration: $('stat-iteration'), lp: $('stat-lp'), best: $('stat-best'), rate: $('stat-rate') },
};

const { showError, clearError, loadWasm } = messages(ui);

const state = {
  tt: null,
  /** The knowledge-base editor (lib/rules-editor.js), once the module has loaded. */
  editor: null,
  sceneJson: '',
  sceneName: '',
  /** The rules in use: the last text that applied without error. */
  rules: '',
  running: false,
  raf: 0,
  dirty: true,
  lastAnalysis: null,
  rate: { t: 0, it: 0 },
  /** The pictures as the library draws them (off screen), and their zoom and pan. */
  viewPicture: null,
  graphPicture: null,
  viewZoom: null,
  graphZoom: null,
  /** The camera view is drawn twice as wide when zoomed in (up to the camera's own width). */
  viewDetail: 1,
  /** The camera view's size at zoom 1, pixels: the canvas keeps it. */
  viewBase: null,
};

function parseSeed(text) {
  const t = String(text).trim();
  if (!/^\d+$/.test(t)) throw new Error(`seed: "${text}" is not a whole number ≥ 0`);
  return BigInt(t);
}

/**
 * What a scene holds. The chain sees estimates; a generated scene's truth says which are false
 * (no object there) and lists the objects hidden under others, which the camera did not see:
 * the objects on the table are the true estimates and the hidden ones.
 */
function describeScene(sceneJson, estimates) {
  let scene = {};
  try {
    scene = JSON.parse(sceneJson);
  } catch {
    // The chain parsed it; nothing more to say.
  }
  const objects = Array.isArray(scene.objects) ? scene.objects : [];
  if (!objects.some((o) => o.truth)) return `${estimates} estimated objects`;
  const falses = objects.filter((o) => o.truth?.false).length;
  const hidden = scene.hidden_objects?.length ?? 0;
  const seen = estimates - falses;
  return `${seen + hidden} objects: ${seen} seen, ${hidden} hidden under them; ${estimates} estimates, ${falses} false`;
}

/** Starts a chain on scene text; on error the old chain stays and the error is thrown. */
function load(sceneJson, name) {
  const tt = new Tabletop(sceneJson, undefined, parseSeed(ui.seed.value), state.rules);
  state.tt?.free();
  state.tt = tt;
  state.sceneJson = sceneJson;
  state.sceneName = name;
  ui.sceneName.textContent = `${name} (${describeScene(sceneJson, tt.objects)})`;
  state.rate = { t: performance.now(), it: 0 };
  state.dirty = true;
  redraw();
}

function generate() {
  const seed = parseSeed(ui.synthSeed.value);
  const n = Number(ui.synthObjects.value);
  if (!Number.isInteger(n) || n < 1 || n > 20) throw new Error(`objects: give a whole number from 1 to 20, not ${ui.synthObjects.value}`);
  const text = tabletopSynth(seed, JSON.stringify({ min_objects: n, max_objects: n }));
  load(text, `synthetic, seed ${seed}`);
}

const fmt = (p) => p.toFixed(3);

function renderTable(a) {
  const rows = a.objects.map((o) => {
    const tr = document.createElement('tr');
    const truth = o.truth ? `${o.truth.hidden ? 'hidden' : ''}${o.truth.hidden && o.truth.false ? ', ' : ''}${o.truth.false ? 'false' : ''}` || '–' : '';
    const cells = [o.id, fmt(o.p_hidden), fmt(o.p_false), fmt(o.supported), fmt(o.supportive), o.hidden, o['false'], truth];
    cells.forEach((c, i) => {
      const td = document.createElement(i === 0 ? 'th' : 'td');
      if (i === 0) td.scope = 'row';
      td.textContent = c;
      if (i === 5 || i === 6) {
        td.className = c;
        const t = o.truth && (i === 5 ? o.truth.hidden : o.truth['false']);
        if (o.truth && c !== 'undecided' && (c === 'true') !== t) td.classList.add('wrong');
      }
      tr.append(td);
    });
    return tr;
  });
  ui.tbody.replaceChildren(...rows);
}

function redraw() {
  const tt = state.tt;
  if (!tt) return;
  const a = JSON.parse(tt.analysisJson());
  state.lastAnalysis = a;
  const v = state.viewZoom.view;
  state.viewDetail = v.zoom >= 1.5 ? 2 : 1;
  tt.drawView(state.viewPicture, VIEW_WIDTH * state.viewDetail);
  if (state.viewDetail === 1) state.viewBase = [state.viewPicture.width, state.viewPicture.height];
  tt.drawGraph(state.graphPicture);
  paintPictures();
  renderTable(a);
  ui.stat.iteration.textContent = String(tt.iteration);
  ui.stat.lp.textContent = tt.logPosterior.toFixed(2);
  ui.stat.best.textContent = tt.bestLogPosterior.toFixed(2);
  state.dirty = false;
}

/** Shows both pictures through their views, on canvases of the pictures' size at zoom 1. */
function paintPictures() {
  const show = (canvas, picture, zoom, [w, h] = [picture.width, picture.height]) => {
    if (!picture.width) return;
    if (canvas.width !== w || canvas.height !== h) {
      canvas.width = w;
      canvas.height = h;
    }
    zoom.draw(canvas, picture);
  };
  show(ui.view, state.viewPicture, state.viewZoom, state.viewBase ?? undefined);
  show(ui.graph, state.graphPicture, state.graphZoom);
}

/** A view moved: shown again at once; the camera view is drawn again if it needs more detail. */
function viewMoved() {
  const detail = state.viewZoom.view.zoom >= 1.5 ? 2 : 1;
  if (detail !== state.viewDetail) attempt(redraw);
  else paintPictures();
}

function frame() {
  state.raf = 0;
  try {
    if (state.running && state.tt) {
      state.tt.runFor(BUDGET_MS);
      const now = performance.now();
      const dt = now - state.rate.t;
      if (dt > 500) {
        ui.stat.rate.textContent = String(Math.round(((state.tt.iteration - state.rate.it) * 1000) / dt));
        state.rate = { t: now, it: state.tt.iteration };
      }
      state.dirty = true;
    }
    if (state.dirty) redraw();
  } catch (err) {
    pause();
    showError(err);
  }
  if (state.running) state.raf = requestAnimationFrame(frame);
}

function play() {
  if (!state.tt || state.running) return;
  state.running = true;
  document.documentElement.dataset.running = 'true';
  ui.run.textContent = 'Pause';
  state.rate = { t: performance.now(), it: state.tt.iteration };
  if (!state.raf) state.raf = requestAnimationFrame(frame);
}
function pause() {
  state.running = false;
  document.documentElement.dataset.running = 'false';
  ui.run.textContent = 'Start';
}

function attempt(fn) {
  try {
    fn();
    return true;
  } catch (err) {
    showError(err);
    return false;
  }
}

/** Checks the editor's text now; returns whether it is usable. */
function checkEditor() {
  return !state.editor.check();
}

function applyRules() {
  const text = ui.rules.value;
  if (!checkEditor()) {
    showError(`The rules have an error (${ui.rulesError.textContent}); the last good rules stay in use.`);
    return;
  }
  if (state.tt) state.tt.setRules(text);
  state.rules = text;
  clearError();
  state.dirty = true;
  redraw();
  ui.status.textContent = 'Rules applied: the chain starts over with them.';
}

function wire() {
  state.viewPicture = document.createElement('canvas');
  state.graphPicture = document.createElement('canvas');
  state.viewZoom = new Viewport(ui.view, { onChange: viewMoved, controls: { className: 'zoom-controls', label: 'Zoom the camera view' } });
  state.graphZoom = new Viewport(ui.graph, { onChange: viewMoved, controls: { className: 'zoom-controls', label: 'Zoom the scene graph' } });
  ui.view.after(state.viewZoom.controls);
  ui.graph.after(state.graphZoom.controls);
  ui.run.addEventListener('click', () => (state.running ? pause() : play()));
  ui.step.addEventListener('click', () => attempt(() => {
    state.tt?.step(100);
    redraw();
  }));
  ui.reset.addEventListener('click', () => attempt(() => {
    if (state.sceneJson) load(state.sceneJson, state.sceneName);
    clearError();
  }));
  ui.synthForm.addEventListener('submit', (ev) => {
    ev.preventDefault();
    if (attempt(generate)) clearError();
  });
  ui.file.addEventListener('change', async () => {
    const f = ui.file.files?.[0];
    if (!f) return;
    const text = await f.text();
    if (attempt(() => load(text, f.name))) clearError();
    ui.file.value = '';
  });
  ui.download.addEventListener('click', () => download('scene.json', state.sceneJson, 'application/json'));
  ui.rulesApply.addEventListener('click', () => attempt(applyRules));
  ui.rulesDefault.addEventListener('click', () => {
    ui.rules.value = tabletopRulesDefault();
    attempt(applyRules);
  });
}

/** Hooks for the browser tests. */
function expose() {
  window.__ksmcmc = {
    snapshot: () => ({
      iteration: state.tt ? state.tt.iteration : 0,
      running: state.running,
      objects: state.tt ? state.tt.objects : 0,
      rows: ui.tbody.rows.length,
      analysis: state.lastAnalysis,
      error: ui.message.hidden ? null : ui.messageText.textContent,
      rulesError: ui.rulesError.textContent,
      rulesUnderlined: document.querySelector('.rules-marks .err')?.textContent ?? null,
      rulesBadLine: state.editor?.badLine ?? 0,
      rulesInUse: state.rules,
      view: state.viewZoom.view.state(),
      graphView: state.graphZoom.view.state(),
      viewDetail: state.viewDetail,
    }),
    synthText: () => tabletopSynth(9),
    /** Bytes of the page's wasm heap (the soak test watches it). */
    heap: () => wasmHeapBytes(),
    /** The scene.json text the chain analyses. */
    sceneText: () => state.sceneJson,
    /** Milliseconds of a whole analysis: synth, construct, `iterations` steps, analysis JSON. */
    bench(objects = 8, iterations = 100, seed = 3) {
      const t0 = performance.now();
      const text = tabletopSynth(seed, JSON.stringify({ min_objects: objects, max_objects: objects }));
      const tt = new Tabletop(text, undefined, 1);
      tt.step(iterations);
      const a = JSON.parse(tt.analysisJson());
      const ms = performance.now() - t0;
      tt.free();
      return { ms, objects: a.objects.length };
    },
  };
}

async function main() {
  wire();
  expose();
  if (!(await loadWasm(init))) return;
  ui.version.textContent = version();
  state.rules = tabletopRulesDefault();
  ui.rules.value = state.rules;
  state.editor = rulesEditor(ui.rules, {
    check: tabletopCheckRules,
    status: ui.rulesError,
    okText: 'The rules parse.',
    gutterId: 'rules-gutter',
    delayMs: 150,
  });
  for (const el of [ui.run, ui.step, ui.reset, ui.generate, ui.file, ui.download, ui.rulesApply, ui.rulesDefault]) el.disabled = false;
  const params = new URLSearchParams(location.search);
  if (params.has('scene')) ui.synthSeed.value = params.get('scene');
  attempt(generate);
  document.documentElement.dataset.state = 'ready';
  if (params.get('autoplay') === '1') play();
}

main();
