// The live mapper page: a data-driven MCMC chain explains an occupancy map with a semantic
// floor plan while you watch. The chain, the pictures and the exports are the library's
// (pkg/ksmcmc.js; the rooms and exports pkg/ksmcmc_plan.js, which the worker loads when the
// best world first has units). The chain runs in a Web Worker (lib/chain-worker.js), so that
// no step of it, however long, blocks a frame of the page; the page draws the pictures the
// worker sends, at most one per animation frame, and asks for the next one when it has drawn
// the last.
//
// This file wires the page: the maps (samples, opened files, a blank map to paint), the
// keyboard, the controls' listeners and the start. The rest is in www/mapper/, by concern:
// state.js (the one state object and the elements), chain.js (the chain in its worker, its
// numbers and plots), weak.js (the weak prior beside it), view.js (the canvas, its view and
// overlays, the 3D view, routes), painting.js, rooms.js (the Rooms table and the room pointed
// at), edits.js (the person's corrections), exports.js (downloads) and hooks.js (window.__ksmcmc).

import init, { chainConfigDefaults, legendJson, Map as OccMap, version } from './pkg/ksmcmc.js';
import { fillMapLegend } from './lib/map-legend.js';
import { onDroppedFiles, readPickedMap } from './lib/files.js';
import { parseIterationsPerFrame } from './lib/plot.js';
import { RemoteChain } from './lib/remote-chain.js';
import { RouteView } from './lib/route-view.js';
import { fetchSampleFile, fetchSampleMap } from './lib/samples.js';
import { Viewport } from './lib/viewport.js';
import { attempt, loadWasm, say, showError, state, ui } from './mapper/state.js';
import { chainFailed, chainSettled, chainWings, invoke, play, reset, setMap, step, toggle } from './mapper/chain.js';
import { setEditMode, undoEdit, wireEdits } from './mapper/edits.js';
import { wireExports } from './mapper/exports.js';
import { expose } from './mapper/hooks.js';
import { abortStroke, onPointerDown, onPointerMove, onPointerUp, setBrush, setPainting } from './mapper/painting.js';
import { onHover, onLeave, onTap, RoomsFeed, showRooms, wireRooms } from './mapper/rooms.js';
import { cellFromEvent, clearReference, fit, refresh3d, requestRedraw, setCloud, setLabels, setReference, setRouting, setUnitLabels, setShow, setView3d, viewChanged } from './mapper/view.js';
import { setCompare } from './mapper/weak.js';

// ---------------------------------------------------------------- maps

async function loadSample(name) {
  state.sampleList.find(name);
  const source = await fetchSampleMap(name);
  await setMap(null, source, { name, label: name, sample: name });
}

/** Loads a map from the picked files: one image, or a map.yaml with the image it names. */
async function openFiles(fileList) {
  const { source, name, label } = await readPickedMap(fileList, ui.classify.value);
  await setMap(null, source, { name, label, uploaded: true });
}

/** A blank map to paint on: one free room inside a two-cell wall, which the chain explains at once. */
async function blankMap() {
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
  await setMap(OccMap.fromCells(w, h, codes), { kind: 'cells', width: w, height: h, codes }, { name: 'painted', label: `blank ${w} × ${h}` });
  setPainting(true);
  ui.stage.scrollIntoView({ block: 'nearest' });
  say(`New ${w} × ${h} map: paint walls into it, then press Start.`);
}

// ---------------------------------------------------------------- keyboard

function onKey(e) {
  if (e.key === 'Escape' && state.route?.active && !e.defaultPrevented) {
    e.preventDefault();
    setRouting(false);
    return;
  }
  const t = e.target;
  if (e.defaultPrevented || t.closest?.('input, textarea, select, [contenteditable]')) return;
  const key = e.key.toLowerCase();
  if ((e.ctrlKey || e.metaKey) && !e.altKey && !e.shiftKey && key === 'z' && state.ready) {
    e.preventDefault();
    undoEdit();
    return;
  }
  if (key === 'escape' && state.editMode) {
    e.preventDefault();
    setEditMode(null);
    return;
  }
  if (e.ctrlKey || e.metaKey || e.altKey) return;
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
    n: () => setUnitLabels(!state.unitLabels),
    p: () => setPainting(!state.painting),
    g: () => setRouting(!state.route.active),
    3: () => setView3d(!state.view3d.open),
  };
  const action = actions[key];
  if (!action || !state.ready) return;
  e.preventDefault();
  action();
}

// ---------------------------------------------------------------- wiring

/** The Chain and Map panels' controls, in the order they were always wired. */
function wireChainAndMap() {
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
  ui.compare.addEventListener('change', () => setCompare(ui.compare.checked));
  ui.stopSettled.addEventListener('change', () => {
    if (state.stats) state.chain.call('stopWhenSettled', { on: ui.stopSettled.checked }).catch(showError);
  });
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
}

/** The View panel: which world is drawn, the overlays and the reference world. */
function wireView() {
  for (const radio of document.querySelectorAll('input[name="show"]')) {
    radio.addEventListener('change', () => setShow(radio.value));
  }
  ui.cloud.addEventListener('change', () => setCloud(ui.cloud.checked));
  ui.labels.addEventListener('change', () => setLabels(ui.labels.checked));
  ui.unitLabels.addEventListener('change', () => setUnitLabels(ui.unitLabels.checked));
  ui.worldFile.addEventListener('change', async () => {
    const file = ui.worldFile.files[0];
    if (file) await attempt(async () => setReference(await file.text(), file.name));
    ui.worldFile.value = '';
  });
  ui.truth.addEventListener('click', () =>
    attempt(async () => {
      const r = await fetchSampleFile(state.sample, 'truth.json');
      setReference(await r.text(), `${state.sample}/truth.json`);
    }),
  );
  ui.referenceClear.addEventListener('click', () => attempt(clearReference));
}

/** The map's viewport (zoom and pan, on both canvases), then the route and 3D view controls. */
function wireViewportRouteAnd3d() {
  state.viewport = new Viewport(ui.canvas, {
    onChange: viewChanged,
    dragPans: () => !state.painting && !state.editMode && !state.route?.active,
    onTap,
    onPinch: abortStroke,
    controls: { className: 'zoom-controls', label: 'Zoom the map' },
  });
  state.viewport.listen(ui.weakCanvas);
  ui.zoomBar.prepend(state.viewport.controls);
  ui.route.toggle.addEventListener('click', () => setRouting(!state.route.active));
  ui.view3d.toggle.addEventListener('click', () => setView3d(!state.view3d.open));
  ui.view3d.form.addEventListener('submit', (e) => {
    e.preventDefault();
    refresh3d();
  });
  ui.view3d.reset.addEventListener('click', () => {
    state.view3d.view?.frame();
    state.view3d.view?.render();
  });
  ui.route.placeholder.addEventListener('change', () => attempt(() => state.route.toPlaceholder(ui.route.placeholder.value)));
  ui.route.form.addEventListener('submit', (e) => {
    e.preventDefault();
    attempt(() => state.route.submit());
  });
}

/** The canvas's pointer: painting strokes, then the room pointed at. */
function wireCanvasPointer() {
  ui.canvas.addEventListener('pointerdown', onPointerDown);
  ui.canvas.addEventListener('pointermove', onPointerMove);
  ui.canvas.addEventListener('pointerup', onPointerUp);
  ui.canvas.addEventListener('pointercancel', onPointerUp);
  ui.canvas.addEventListener('pointermove', onHover);
  ui.canvas.addEventListener('pointerleave', onLeave);
}

function wire() {
  wireChainAndMap();
  wireView();

  wireExports();

  // The viewport's listeners before the painting's: a painting stroke asks it whether a pinch
  // is going on.
  wireViewportRouteAnd3d();
  wireEdits();
  wireCanvasPointer();
  wireRooms();
  document.addEventListener('keydown', onKey);

  onDroppedFiles(ui.stage, (files) => attempt(() => openFiles(files)));
  new ResizeObserver(() => fit()).observe(ui.stage);
  window.addEventListener('resize', fit);
}

async function main() {
  wire();
  expose();
  if (!(await loadWasm(init))) return;
  state.chain = new RemoteChain(chainFailed, chainSettled);
  state.chain.onWings = chainWings;
  // The best world is drawn room by room once its plan is made: draw it again after each reply.
  state.rooms = new RoomsFeed(() => state.chain, showRooms, () => state.show === 'best' && requestRedraw());
  state.route = new RouteView({ ...ui.route, canvas: ui.canvas }, {
    plan: (from, to) => invoke('route', from[0], from[1], to[0], to[1]),
    placeholders: () => invoke('placeholdersJson'),
    rooms: () => state.rooms.rooms,
    size: () => ({ width: state.map.width, height: state.map.height }),
    cellOf: (e) => cellFromEvent(e),
  });
  ui.version.textContent = version();
  fillMapLegend(ui.mapLegend, legendJson(), { wall: 'walls', door: 'doors', unknown: 'untyped' });
  setBrush(ui.brush.value);
  for (const el of [ui.file, ui.blankCreate, ui.worldFile]) el.disabled = false;

  const params = new URLSearchParams(location.search);
  if (params.has('seed')) ui.seed.value = params.get('seed');
  if (params.has('ipf')) ui.ipf.value = params.get('ipf');
  ui.compare.checked = false;
  try {
    await state.sampleList.fill(params.get('sample') ?? 'office-small');
    ui.sampleLoad.disabled = false;
    ui.sample.addEventListener('change', () => state.sampleList.describe());
  } catch (err) {
    ui.sampleHint.textContent = `The samples did not load (${err.message}): \`make demo\` copies them into www/samples. Open or paint a map instead.`;
  }
  state.ready = true;
  const first = state.sampleList.samples.length > 0 ? attempt(() => loadSample(ui.sample.value)) : attempt(blankMap);
  await first;
  if (!state.stats) await attempt(blankMap);
  document.documentElement.dataset.state = 'ready';
  if (params.get('autoplay') === '1') play();
}

main();
