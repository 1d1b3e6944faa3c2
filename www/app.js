// The Maps page: generate, open or paint an occupancy map; the wasm library classifies and
// renders it. All map logic is in the library (pkg/ksmcmc.js; the generator is
// pkg/ksmcmc_synth.js); this file is wiring.

import init, { Map as OccMap, drawToCanvas, version } from './pkg/ksmcmc.js';
import initSynth, { synth } from './pkg/ksmcmc_synth.js';
import { TOOLS, MAX_BRUSH, brushOffsets, stamp, strokeTo, cellAt } from './lib/paint.js';
import { planOpen, pickYamlImage, stem, parseSeed, onDroppedFiles } from './lib/files.js';
import { messages } from './lib/messages.js';
import { download } from './lib/download.js';

const $ = (id) => document.getElementById(id);
const ui = {
  message: $('message'),
  messageText: $('message-text'),
  messageClose: $('message-close'),
  status: $('status'),
  version: $('version'),
  seed: $('seed'),
  seedRandom: $('seed-random'),
  synthConfig: $('synth-config'),
  generateForm: $('generate-form'),
  generate: $('generate'),
  file: $('file'),
  brush: $('brush'),
  brushValue: $('brush-value'),
  undo: $('undo'),
  blankForm: $('blank-form'),
  blankWidth: $('blank-width'),
  blankHeight: $('blank-height'),
  blankFill: $('blank-fill'),
  blankCreate: $('blank-create'),
  stage: $('stage'),
  canvas: $('map'),
  cursor: $('cursor'),
  cursorPos: $('cursor-pos'),
  mapName: $('map-name'),
  size: $('size'),
  free: $('count-free'),
  unknown: $('count-unknown'),
  occupied: $('count-occupied'),
  downloadPgm: $('download-pgm'),
  downloadYaml: $('download-yaml'),
  downloadTruth: $('download-truth'),
  downloadLabels: $('download-labels'),
};

const { clearError, say, attempt, loadWasm } = messages(ui);

/** Undo keeps at most this many strokes and this many bytes of snapshots. */
const UNDO_STEPS = 30;
const UNDO_BYTES = 64 << 20;
/** The largest map the blank-map form makes (the library's own limit is far larger). */
const MAX_BLANK = 2000;

const state = {
  /** The map as shown (a wasm Map). */
  map: null,
  /** The map as loaded or generated: its resolution and origin go into downloaded YAML. */
  source: null,
  /** Cell codes as loaded (the eraser restores these) and as painted. */
  base: null,
  codes: null,
  width: 0,
  height: 0,
  /** Download file stem, e.g. "map" -> map.pgm, map.yaml. */
  name: 'map',
  /** For synthetic maps: { json, labelsPgm } of the ground truth. */
  truth: null,
  tool: 'occupied',
  brush: 3,
  offsets: brushOffsets(3),
  cursor: [0, 0],
  cursorShown: false,
  /** The cell where the current stroke last painted, or null between strokes. */
  strokeAt: null,
  spaceDown: false,
  undo: [],
  renderPending: false,
};

// ---------------------------------------------------------------- the map

/** Shows a new map, replacing (and freeing) the old one. */
function setMap(map, { name, label, truth = null }) {
  const old = [state.map, state.source];
  state.map = map;
  state.source = map;
  for (const m of new Set(old)) if (m && m !== map) m.free();
  state.width = map.width;
  state.height = map.height;
  state.base = map.cells();
  state.codes = state.base.slice();
  state.name = name;
  state.truth = truth;
  state.undo = [];
  state.strokeAt = null;
  state.cursor = [Math.floor(state.width / 2), Math.floor(state.height / 2)];
  ui.mapName.textContent = label ? `· ${label}` : '';
  ui.canvas.setAttribute('aria-label', `Classified map${label ? `, ${label}` : ''}, ${state.width} by ${state.height} cells`);
  ui.downloadPgm.querySelector('.fname').textContent = `${name}.pgm`;
  ui.downloadYaml.querySelector('.fname').textContent = `${name}.yaml`;
  ui.downloadPgm.disabled = false;
  ui.downloadYaml.disabled = false;
  ui.downloadTruth.hidden = !truth;
  ui.downloadLabels.hidden = !truth;
  ui.undo.disabled = true;
  draw();
  fit();
  placeCursor();
}

/** Renders the current map onto the canvas with the wasm renderer and updates the counts. */
function draw() {
  drawToCanvas(ui.canvas, state.map, undefined, 1, false);
  const c = state.map.counts();
  const n = state.width * state.height;
  const fmt = (k) => `${k.toLocaleString('en-US')} (${((100 * k) / n).toFixed(1)} %)`;
  ui.size.textContent = `${state.width} × ${state.height}`;
  ui.free.textContent = fmt(c.free);
  ui.unknown.textContent = fmt(c.unknown);
  ui.occupied.textContent = fmt(c.occupied);
}

/** Rebuilds the map from the painted codes and redraws, at most once per frame. */
function scheduleRender() {
  if (state.renderPending) return;
  state.renderPending = true;
  requestAnimationFrame(() => {
    state.renderPending = false;
    attempt(() => {
      const painted = OccMap.fromCells(state.width, state.height, state.codes);
      if (state.map !== state.source) state.map.free();
      state.map = painted;
      draw();
    });
  });
}

/** Sizes the canvas on screen: as large as fits, whole multiples of the map when enlarged. */
function fit() {
  if (!state.map) return;
  const box = ui.stage.getBoundingClientRect();
  const availW = Math.max(64, box.width - 16);
  const availH = Math.max(160, Math.min(window.innerHeight * 0.72, 1400));
  let s = Math.min(availW / state.width, availH / state.height);
  if (s >= 1) s = Math.floor(s);
  ui.canvas.style.width = `${Math.max(1, Math.round(state.width * s))}px`;
  ui.canvas.style.height = `${Math.max(1, Math.round(state.height * s))}px`;
  // Shrinking with nearest-neighbour drops thin walls; smooth it instead.
  ui.canvas.classList.toggle('smooth', s < 1);
  placeCursor();
}

// ---------------------------------------------------------------- painting

function pushUndo() {
  state.undo.push(state.codes.slice());
  let bytes = state.undo.reduce((a, u) => a + u.length, 0);
  while (state.undo.length > UNDO_STEPS || (state.undo.length > 1 && bytes > UNDO_BYTES)) {
    bytes -= state.undo.shift().length;
  }
  ui.undo.disabled = false;
}

function undo() {
  const prev = state.undo.pop();
  if (!prev) return;
  state.codes = prev;
  ui.undo.disabled = state.undo.length === 0;
  scheduleRender();
  say('Undone.');
}

function toolValue() {
  return TOOLS[state.tool];
}

/** Starts a stroke at a cell. */
function strokeStart(cell) {
  if (!state.map) return;
  pushUndo();
  state.strokeAt = cell;
  if (stamp(state.codes, state.base, state.width, state.height, cell[0], cell[1], state.offsets, toolValue())) {
    scheduleRender();
  }
}

/** Continues the stroke to a cell. */
function strokeMove(cell) {
  if (!state.strokeAt) return;
  const changed = strokeTo(
    state.codes, state.base, state.width, state.height, state.strokeAt, cell, state.offsets, toolValue(),
  );
  state.strokeAt = cell;
  if (changed) scheduleRender();
}

function strokeEnd() {
  state.strokeAt = null;
}

function cellFromEvent(e) {
  const r = ui.canvas.getBoundingClientRect();
  return cellAt(e.clientX - r.left, e.clientY - r.top, r, state.width, state.height);
}

function placeCursor() {
  if (!state.map || !state.cursorShown) {
    ui.cursor.hidden = true;
    return;
  }
  const w = ui.canvas.clientWidth / state.width;
  const h = ui.canvas.clientHeight / state.height;
  const reach = Math.floor(state.brush / 2);
  const [x, y] = state.cursor;
  ui.cursor.style.left = `${(x - reach) * w}px`;
  ui.cursor.style.top = `${(y - reach) * h}px`;
  ui.cursor.style.width = `${Math.max(4, (2 * reach + 1) * w)}px`;
  ui.cursor.style.height = `${Math.max(4, (2 * reach + 1) * h)}px`;
  ui.cursor.hidden = false;
}

function setTool(tool) {
  state.tool = tool;
  const radio = document.querySelector(`input[name="tool"][value="${tool}"]`);
  if (radio) radio.checked = true;
}

function setBrush(size) {
  const s = Math.min(MAX_BRUSH, Math.max(1, Math.round(Number(size)) || 1));
  state.brush = s;
  state.offsets = brushOffsets(s);
  ui.brush.value = String(s);
  ui.brushValue.textContent = String(s);
  placeCursor();
}

function onPointerDown(e) {
  if (!state.map || (e.pointerType === 'mouse' && e.button !== 0)) return;
  e.preventDefault();
  ui.canvas.focus({ preventScroll: true });
  ui.canvas.setPointerCapture(e.pointerId);
  const cell = cellFromEvent(e);
  state.cursor = cell;
  state.cursorShown = true;
  placeCursor();
  strokeStart(cell);
}

function onPointerMove(e) {
  if (!state.map) return;
  const cell = cellFromEvent(e);
  state.cursor = cell;
  state.cursorShown = true;
  placeCursor();
  if (state.strokeAt) strokeMove(cell);
}

function onPointerUp(e) {
  if (ui.canvas.hasPointerCapture(e.pointerId)) ui.canvas.releasePointerCapture(e.pointerId);
  strokeEnd();
}

const ARROWS = { ArrowLeft: [-1, 0], ArrowRight: [1, 0], ArrowUp: [0, -1], ArrowDown: [0, 1] };
const TOOL_KEYS = { 1: 'occupied', 2: 'free', 3: 'unknown', 4: 'eraser' };

function onCanvasKey(e) {
  if (!state.map || e.altKey) return;
  if ((e.ctrlKey || e.metaKey) && e.key.toLowerCase() === 'z') {
    e.preventDefault();
    undo();
    return;
  }
  if (e.ctrlKey || e.metaKey) return;
  if (ARROWS[e.key]) {
    e.preventDefault();
    const step = e.shiftKey ? 10 : 1;
    const [dx, dy] = ARROWS[e.key];
    const x = Math.min(state.width - 1, Math.max(0, state.cursor[0] + dx * step));
    const y = Math.min(state.height - 1, Math.max(0, state.cursor[1] + dy * step));
    state.cursor = [x, y];
    state.cursorShown = true;
    if (state.spaceDown) strokeMove(state.cursor);
    placeCursor();
    ui.cursorPos.textContent = `Cursor at column ${x}, row ${y}`;
  } else if (e.key === ' ' || e.key === 'Enter') {
    e.preventDefault();
    if (e.repeat) return;
    state.cursorShown = true;
    placeCursor();
    strokeStart(state.cursor);
    if (e.key === ' ') state.spaceDown = true;
    else strokeEnd();
    ui.cursorPos.textContent = `Painted ${state.tool} at column ${state.cursor[0]}, row ${state.cursor[1]}`;
  } else if (TOOL_KEYS[e.key]) {
    e.preventDefault();
    setTool(TOOL_KEYS[e.key]);
    ui.cursorPos.textContent = `Tool: ${state.tool}`;
  } else if (e.key === '[' || e.key === ']') {
    e.preventDefault();
    setBrush(state.brush + (e.key === ']' ? 1 : -1));
    ui.cursorPos.textContent = `Brush: ${state.brush} cells`;
  }
}

function onCanvasKeyUp(e) {
  if (e.key === ' ') {
    state.spaceDown = false;
    strokeEnd();
  }
}

// ---------------------------------------------------------------- getting maps

function generate() {
  return attempt(() => {
    const seed = parseSeed(ui.seed.value);
    const config = ui.synthConfig.value.trim() || undefined;
    const t0 = performance.now();
    const s = synth(seed, config);
    try {
      const truth = { json: s.truthJson, labelsPgm: s.labelsPgm };
      setMap(OccMap.fromYaml(s.mapYaml, s.mapPgm), { name: 'map', label: `synthetic, seed ${seed}`, truth });
    } finally {
      s.free();
    }
    clearError();
    say(`Generated seed ${seed} in ${Math.round(performance.now() - t0)} ms.`);
  });
}

async function bytesOf(file) {
  return new Uint8Array(await file.arrayBuffer());
}

async function openFiles(fileList) {
  const files = [...fileList];
  if (files.length === 0) return;
  await attempt(async () => {
    const byName = new Map(files.map((f) => [f.name, f]));
    const plan = planOpen(files.map((f) => f.name));
    if (plan.kind === 'error') throw new Error(plan.message);
    let map;
    let imageName;
    if (plan.kind === 'image') {
      imageName = plan.image;
      map = OccMap.fromBytes(await bytesOf(byName.get(imageName)));
    } else {
      let text;
      try {
        text = new TextDecoder('utf-8', { fatal: true }).decode(await bytesOf(byName.get(plan.yaml)));
      } catch {
        throw new Error(`${plan.yaml} is not UTF-8 text, so it is not a ROS map.yaml.`);
      }
      const pick = pickYamlImage(plan.yaml, text, plan.images);
      if (pick.message) throw new Error(pick.message);
      imageName = pick.image;
      map = OccMap.fromYaml(text, await bytesOf(byName.get(imageName)));
    }
    setMap(map, { name: stem(imageName), label: imageName });
    clearError();
    say(`Opened ${files.map((f) => f.name).join(' + ')}.`);
  });
}

function createBlank() {
  return attempt(() => {
    const read = (input, what) => {
      const v = Number(input.value);
      if (!Number.isInteger(v) || v < 1 || v > MAX_BLANK) {
        throw new Error(`${what} must be a whole number from 1 to ${MAX_BLANK}, not "${input.value}".`);
      }
      return v;
    };
    const w = read(ui.blankWidth, 'Width');
    const h = read(ui.blankHeight, 'Height');
    const codes = new Uint8Array(w * h).fill(Number(ui.blankFill.value));
    setMap(OccMap.fromCells(w, h, codes), { name: 'painted', label: `blank ${w} × ${h}` });
    clearError();
    say(`New ${w} × ${h} map. Paint on it.`);
    ui.canvas.focus();
  });
}

// ---------------------------------------------------------------- downloads

function save(name, data, type) {
  download(name, data, type);
  say(`Saved ${name}.`);
}

// ---------------------------------------------------------------- wiring

function wire() {
  ui.generateForm.addEventListener('submit', (e) => {
    e.preventDefault();
    generate();
  });
  ui.seedRandom.addEventListener('click', () => {
    ui.seed.value = String(crypto.getRandomValues(new Uint32Array(1))[0]);
    generate();
  });
  ui.file.addEventListener('change', async () => {
    await openFiles(ui.file.files);
    ui.file.value = '';
  });
  for (const radio of document.querySelectorAll('input[name="tool"]')) {
    radio.addEventListener('change', () => setTool(radio.value));
  }
  ui.brush.addEventListener('input', () => setBrush(ui.brush.value));
  ui.undo.addEventListener('click', undo);
  ui.blankForm.addEventListener('submit', (e) => {
    e.preventDefault();
    createBlank();
  });

  ui.canvas.addEventListener('pointerdown', onPointerDown);
  ui.canvas.addEventListener('pointermove', onPointerMove);
  ui.canvas.addEventListener('pointerup', onPointerUp);
  ui.canvas.addEventListener('pointercancel', onPointerUp);
  ui.canvas.addEventListener('pointerleave', () => {
    if (!state.strokeAt && document.activeElement !== ui.canvas) {
      state.cursorShown = false;
      placeCursor();
    }
  });
  ui.canvas.addEventListener('keydown', onCanvasKey);
  ui.canvas.addEventListener('keyup', onCanvasKeyUp);
  ui.canvas.addEventListener('focus', () => {
    state.cursorShown = true;
    placeCursor();
  });
  ui.canvas.addEventListener('blur', () => {
    state.spaceDown = false;
    strokeEnd();
    state.cursorShown = false;
    placeCursor();
  });
  document.addEventListener('keydown', (e) => {
    const editing = e.target.closest?.('input, textarea, select');
    if (!editing && e.target !== ui.canvas && (e.ctrlKey || e.metaKey) && e.key.toLowerCase() === 'z') {
      e.preventDefault();
      undo();
    }
  });

  onDroppedFiles(ui.stage, openFiles);

  ui.downloadPgm.addEventListener('click', () =>
    attempt(() => save(`${state.name}.pgm`, state.map.toPgm(), 'image/x-portable-graymap')),
  );
  // The YAML comes from the map as loaded, which keeps its resolution and origin; painting
  // changes cells, never the size, so it describes the painted map as well.
  ui.downloadYaml.addEventListener('click', () =>
    attempt(() => save(`${state.name}.yaml`, state.source.toYaml(`${state.name}.pgm`), 'application/yaml')),
  );
  ui.downloadTruth.addEventListener('click', () => save('truth.json', state.truth.json, 'application/json'));
  ui.downloadLabels.addEventListener('click', () =>
    save('truth_labels.pgm', state.truth.labelsPgm, 'image/x-portable-graymap'),
  );

  new ResizeObserver(() => fit()).observe(ui.stage);
  window.addEventListener('resize', fit);
}

async function main() {
  wire();
  if (!(await loadWasm(() => Promise.all([init(), initSynth()])))) return;
  ui.version.textContent = version();
  for (const el of [ui.seed, ui.seedRandom, ui.synthConfig, ui.generate, ui.file, ui.blankCreate]) {
    el.disabled = false;
  }
  setBrush(ui.brush.value);
  await generate();
  document.documentElement.dataset.state = 'ready';
}

main();
