// What the live mapper shows and how: the map canvas drawn through the zoom and pan (from the
// pictures the worker sends, kept to draw again when the view moves), the canvases' size on
// the page, what the picture shows (current, best or reference world, the cloud, the labels),
// the reference world, the 3D view of the best world (three.js, loaded when first opened) and
// route mode. Other parts draw over the map through it (the room pointed at, the edits' ring
// and line), and ask it to redraw rather than draw themselves.

import { cellAt } from '../lib/paint.js';
import { formatNumber } from '../lib/plot.js';
import { detailScale } from '../lib/viewport.js';
import { clearError, say, state, ui } from './state.js';
import { invoke, schedule, takeStats } from './chain.js';
import { drawOverlay } from './edits.js';
import { setPainting } from './painting.js';
import { placeRoomInfo } from './rooms.js';

/** The most pixels per cell the page draws for the whole map (more only costs time per frame). */
const MAX_SCALE = 3;
/**
 * The largest picture the worker draws when zoomed in, pixels: it draws the whole map, so the
 * detail of a large map's zoom is limited by the time a picture takes.
 */
const MAX_PICTURE_PIXELS = 6_000_000;

// ---------------------------------------------------------------- drawing

/** Draws at the next animation frame (once, however often it is asked). */
export function requestRedraw() {
  state.redrawPending = true;
  if (state.weak) state.weak.redrawPending = true;
  schedule();
}

export function drawBitmap(canvas, bitmap) {
  if (canvas.width !== bitmap.width || canvas.height !== bitmap.height) {
    canvas.width = bitmap.width;
    canvas.height = bitmap.height;
  }
  const ctx = canvas.getContext('2d');
  ctx.clearRect(0, 0, canvas.width, canvas.height);
  ctx.drawImage(bitmap, 0, 0);
  bitmap.close();
}

/** The main chain's picture, kept and drawn through the view, with the room pointed at. */
export function showPicture(picture) {
  state.shown?.close();
  state.shown = picture;
  paintMain();
}

/** Draws the main picture (or, during a stroke, the painted cells) through the view. */
export function paintMain() {
  if (state.painting && state.strokeAt && state.paintCanvas) {
    state.viewport.draw(ui.canvas, state.paintCanvas);
    return;
  }
  if (!state.shown) return;
  state.viewport.draw(ui.canvas, state.shown);
  const mask = state.hover.mask;
  const m = state.map;
  if (mask && m) {
    state.viewport.draw(ui.canvas, mask.canvas, { clear: false, x: mask.x, y: mask.y, width: m.width, height: m.height });
  }
}

export function paintWeak() {
  if (state.weak && state.weakShown) state.viewport.draw(ui.weakCanvas, state.weakShown);
}

/**
 * The view moved: both pictures are drawn again at once from what was last received, and a
 * sharper one is asked for if the zoom needs more pixels per cell.
 */
export function viewChanged() {
  paintMain();
  paintWeak();
  updateDrawScale();
  placeRoomInfo();
}

/** The worker's drawing scale for the zoom: `scale` for the whole map, more when zoomed in. */
function updateDrawScale() {
  const m = state.map;
  if (!m) return;
  const v = state.viewport.view;
  const s = v.isReset ? state.scale : Math.max(state.scale, detailScale(state.scale, v.zoom, m.width * m.height, { maxPixels: MAX_PICTURE_PIXELS }));
  if (s === state.drawScale) return;
  state.drawScale = s;
  requestRedraw();
}

/**
 * Sizes the canvas on screen to fit the stage, and picks the drawing scale: enough pixels per
 * cell for the screen's resolution (at most 3), so that the picture is shrunk smoothly rather
 * than blown up, except for small maps on large screens.
 */
export function fit() {
  const m = state.map;
  if (!m) return;
  const box = ui.stage.getBoundingClientRect();
  // Side by side when comparing, unless the stage is narrow (a phone): then stacked.
  const sideBySide = state.weak && box.width >= 640;
  const availW = Math.max(64, sideBySide ? Math.floor((box.width - 40) / 2) : box.width - 16);
  const availH = Math.max(200, Math.min(window.innerHeight * 0.7, 1200));
  const s = Math.min(availW / m.width, availH / m.height);
  for (const c of [ui.canvas, ui.weakCanvas]) {
    c.style.width = `${Math.max(1, Math.round(m.width * s))}px`;
    c.style.height = `${Math.max(1, Math.round(m.height * s))}px`;
  }
  const dpr = globalThis.devicePixelRatio || 1;
  state.scale = Math.min(MAX_SCALE, Math.max(1, Math.ceil(s * dpr - 0.01)));
  // Shrinking with nearest-neighbour drops thin lines: smooth it; enlarging stays crisp.
  ui.canvas.classList.toggle('smooth', state.scale >= s * dpr);
  ui.weakCanvas.classList.toggle('smooth', state.scale >= s * dpr);
  // The canvases hold the whole map at `scale`; zoomed pictures are drawn into them.
  for (const c of [ui.canvas, ui.weakCanvas]) {
    if (c.width !== m.width * state.scale || c.height !== m.height * state.scale) {
      c.width = m.width * state.scale;
      c.height = m.height * state.scale;
    }
  }
  if (state.weak) state.weak.redrawPending = true;
  state.route?.resize(state.scale);
  drawOverlay();
  requestRedraw();
  viewChanged();
}

// ---------------------------------------------------------------- what the picture shows, and the reference

export function setShow(show) {
  if (show === 'reference' && !state.stats?.hasReference) return;
  state.show = show;
  const radio = document.querySelector(`input[name="show"][value="${show}"]`);
  if (radio) radio.checked = true;
  requestRedraw();
}

export function setCloud(on) {
  state.cloud = on;
  ui.cloud.checked = on;
  requestRedraw();
}

/** Room labels on the map (L): the rooms of the Rooms table, once the best world's rooms are known. */
export function setLabels(on) {
  state.labels = on;
  ui.labels.checked = on;
  requestRedraw();
}

/** Unit labels instead of room labels (N): each unit of the world drawn, with its type. */
export function setUnitLabels(on) {
  state.unitLabels = on;
  ui.unitLabels.checked = on;
  requestRedraw();
}

export function updateReferenceControls() {
  const has = Boolean(state.stats?.hasReference);
  ui.showReference.disabled = !has;
  ui.referenceClear.disabled = !has;
  if (!has && state.show === 'reference') setShow('best');
}

export async function setReference(text, name) {
  takeStats(await state.chain.call('setReference', { json: text }));
  state.referenceJson = text;
  state.referenceName = name;
  updateReferenceControls();
  setShow('reference');
  clearError();
  say(`Showing ${name} as the reference world.`);
}

/** Drops the reference world. */
export async function clearReference() {
  takeStats(await state.chain.call('setReference', { json: null }));
  state.referenceJson = null;
  updateReferenceControls();
  say('Reference cleared.');
  requestRedraw();
}

// ---------------------------------------------------------------- 3D view

/** The heights in the 3D view's form, for `worldGlb`. */
export function heights() {
  return { wallHeight: Number(ui.view3d.wall.value), doorHeight: Number(ui.view3d.door.value) };
}

/** Opens or closes the 3D view; opening it the first time loads three.js. */
export async function setView3d(on) {
  const v = state.view3d;
  if (on === v.open) return;
  v.open = on;
  ui.view3d.toggle.setAttribute('aria-pressed', String(on));
  ui.view3d.panel.hidden = !on;
  if (!on) return;
  if (!v.view) {
    ui.view3d.status.textContent = 'Loading the 3D viewer…';
    try {
      const { View3d } = await import('../lib/view3d.js');
      v.view = new View3d(ui.view3d.canvas);
      new ResizeObserver(() => v.view.resize()).observe(ui.view3d.canvas);
    } catch (err) {
      v.error = `The 3D viewer did not load (${err.message}): \`make demo\` copies three.js into www/vendor.`;
      ui.view3d.status.textContent = v.error;
      return;
    }
  }
  v.view.resize();
  ui.view3d.panel.scrollIntoView({ block: 'nearest' });
  await refresh3d();
}

/** Shows the best world's world.glb in the 3D view, if it is open. */
export async function refresh3d() {
  const v = state.view3d;
  if (!v.open || !v.view || !state.stats) return;
  const token = ++v.token;
  const iteration = state.stats.iteration;
  try {
    const bytes = await invoke('worldGlb', heights());
    if (token !== v.token) return;
    await v.view.show(bytes);
    v.error = null;
    v.shown = token;
    ui.view3d.status.textContent = `The best world at iteration ${formatNumber(iteration)}: ${formatNumber(bytes.length)} bytes of world.glb.`;
    ui.view3d.panel.dataset.state = 'ready';
  } catch (err) {
    if (token !== v.token) return;
    v.error = err instanceof Error ? err.message : String(err);
    ui.view3d.status.textContent = `No 3D world: ${v.error}`;
  }
}

// ---------------------------------------------------------------- routes

/** Turns route mode on or off: clicks on the map then pick the route's start and goal. */
export function setRouting(on) {
  if (!state.route || on === state.route.active) return;
  if (on && state.painting) setPainting(false);
  // The route's layer is drawn at the whole map's scale: route mode shows the whole map.
  if (on) state.viewport?.reset?.();
  state.route.setActive(on);
  state.route.show();
  say(on ? 'Route mode: click the start, then the goal on the map. Esc leaves it.' : 'Left route mode.');
}

/** The cell under a pointer event, through the zoom and pan. */
export function cellFromEvent(e) {
  const [u, v] = state.viewport.contentAt(e, ui.canvas);
  return cellAt(u, v, { width: 1, height: 1 }, state.map.width, state.map.height);
}
