// The person's hand on the map canvas: painting strokes (the painted cells shown at once, then
// handed to the chain, which goes on from its world on the painted map) and the dispatch of a
// press on the map to route mode, painting or the edits, whichever is on.

import { drawToCanvas, Map as OccMap } from '../pkg/ksmcmc.js';
import { brushOffsets, MAX_BRUSH, stamp, strokeTo, TOOLS } from '../lib/paint.js';
import { formatNumber } from '../lib/plot.js';
import { attempt, clearError, say, showError, state, ui } from './state.js';
import { pause, schedule, takeStats } from './chain.js';
import { editPointerDown, editPointerMove, editPointerUp, syncEdits } from './edits.js';
import { cellFromEvent, paintMain, requestRedraw, setRouting } from './view.js';

export function setPainting(on) {
  if (on) setRouting(false);
  state.painting = on;
  ui.paint.checked = on;
  ui.canvas.classList.toggle('painting', on);
  if (on) {
    pause();
    say('Painting: drag on the map. After each stroke the chain goes on from its world on the painted map; Reset starts over.');
  }
}

/** Shows the painted cells (without a world) while a stroke goes on, through the view. */
function showPainted() {
  if (!state.strokeAt) return;
  attempt(() => {
    const painted = OccMap.fromCells(state.map.width, state.map.height, state.codes);
    try {
      state.paintCanvas ??= document.createElement('canvas');
      drawToCanvas(state.paintCanvas, painted, undefined, 1, false);
    } finally {
      painted.free();
    }
    paintMain();
  });
}

/** A pinch began during a stroke: the stroke is undone (two fingers zoom, they do not paint). */
export function abortStroke() {
  if (!state.strokeAt) return;
  state.strokeAt = null;
  state.codes = state.strokeUndo ?? state.base.slice();
  paintMain();
}

/** Shows the painted cells at the next animation frame (once, however often it is asked). */
function schedulePaint() {
  if (state.paintFramePending) return;
  state.paintFramePending = true;
  requestAnimationFrame(() => {
    state.paintFramePending = false;
    showPainted();
  });
}

export function onPointerDown(e) {
  if (state.route?.active && state.map && (e.pointerType !== 'mouse' || e.button === 0)) {
    e.preventDefault();
    state.route.pick(e);
    return;
  }
  if (!state.map || (e.pointerType === 'mouse' && e.button !== 0)) return;
  // A second finger: the viewport pinches.
  if (state.viewport.pointers.size > 1) return;
  if (!state.painting) {
    editPointerDown(e);
    return;
  }
  e.preventDefault();
  ui.canvas.setPointerCapture?.(e.pointerId);
  state.strokeUndo = state.codes.slice();
  state.strokeAt = cellFromEvent(e);
  const [x, y] = state.strokeAt;
  stamp(state.codes, state.base, state.map.width, state.map.height, x, y, state.offsets, TOOLS[state.tool]);
  showPainted();
}

export function onPointerMove(e) {
  if (state.splitDrag) editPointerMove(e);
  if (!state.strokeAt || state.viewport.busy) return;
  const cell = cellFromEvent(e);
  const { width, height } = state.map;
  if (strokeTo(state.codes, state.base, width, height, state.strokeAt, cell, state.offsets, TOOLS[state.tool])) schedulePaint();
  state.strokeAt = cell;
}

/**
 * The stroke is done: the painted map replaces the map, and the chain takes it and goes on from
 * its world (`updateMap`): where the map did not change, the world stays. Reset starts over.
 */
export async function onPointerUp(e) {
  if (state.splitDrag) editPointerUp(e);
  if (!state.strokeAt) return;
  state.strokeAt = null;
  // The painted cells stay on the canvas until the painted map's picture comes.
  state.shown?.close();
  state.shown = null;
  const { width, height } = state.map;
  try {
    const codes = state.codes.slice();
    const painted = OccMap.fromCells(width, height, codes);
    const source = { kind: 'cells', width, height, codes };
    let reply;
    try {
      reply = await state.chain.call('updateMap', { source });
    } catch (err) {
      painted.free();
      throw err;
    }
    state.map.free();
    state.map = painted;
    followMap(reply, source);
    clearError();
    say(
      `Painted: ${formatNumber(reply.changed)} cell${reply.changed === 1 ? '' : 's'} changed. The chain goes on from its world ` +
        `on the painted map (iteration ${formatNumber(reply.stats.iteration)}); Start runs it, Reset starts over.`,
    );
  } catch (err) {
    state.codes = state.strokeUndo ?? state.base.slice();
    showError(new Error(`${err instanceof Error ? err.message : err} (the stroke was undone)`));
    requestRedraw();
  }
}

/**
 * The chain took a changed map and went on (the same chain: its trace and statistics carry
 * on). The rooms, the route, the 3D view and the edits are read again, and the weak prior's
 * chain, if shown, takes the same map.
 */
function followMap({ stats, changed }, source) {
  takeStats(stats);
  state.source = source;
  if (changed > 0) {
    state.rooms.request();
    syncEdits();
    const weak = state.weak;
    if (weak?.stats) {
      const token = weak.token;
      weak.chain.call('updateMap', { source }).then(
        (reply) => {
          if (state.weak !== weak || token !== weak.token) return;
          weak.stats = reply.stats;
          weak.rooms.request();
          weak.redrawPending = true;
          schedule();
        },
        (err) => showError(new Error(`The weak prior's chain did not take the painted map: ${err.message}`)),
      );
    }
  }
  requestRedraw();
}

export function setBrush(size) {
  const s = Math.min(MAX_BRUSH, Math.max(1, Math.round(Number(size)) || 1));
  state.brush = s;
  state.offsets = brushOffsets(s);
  ui.brush.value = String(s);
  ui.brushValue.textContent = String(s);
}
