// The live mapper's hooks for the browser tests and the curious: `window.__ksmcmc`, the
// page's numbers and the chain's exports read from the running chain, and `idle()`, which
// resolves once the page has drawn the chain's latest state. The tests (tests/e2e) and
// scripts/soak.mjs read these names: keep them.

import { state, ui } from './state.js';
import { invoke } from './chain.js';

/** For tests and the curious: the page's numbers, read from the running chain. */
export function expose() {
  window.__ksmcmc = {
    /** The chain's exports and report, as promises (the chain is in a worker). */
    mapper: Object.fromEntries(['bestWorldJson', 'worldJson', 'labelsPgm', 'graphJson', 'reportJson', 'toPng', 'geojson', 'svg', 'worldGlb', 'roomsJson', 'editsJson', 'setEdits'].map((name) => [name, (...args) => invoke(name, ...args)])),
    /** The weak prior's chain beside it (when compared): its exports and numbers. */
    weak: {
      invoke: (name, ...args) => state.weak.chain.call('invoke', { name, args }),
      snapshot: () => (state.weak ? { ...state.weak.stats, rooms: state.weak.rooms.rooms } : null),
    },
    /** Bytes of the wasm heaps: the chain's worker and, when compared, the weak prior's. */
    async heap() {
      return { chain: await state.chain.call('heap'), weak: state.weak ? await state.weak.chain.call('heap') : null };
    },
    /** The 3D view: open, which request it shows, its error and the model's node names. */
    view3d: () => {
      const v = state.view3d;
      return { open: v.open, loaded: Boolean(v.view), shown: v.shown, token: v.token, error: v.error, nodes: v.view?.nodeNames() ?? [] };
    },
    /** Route mode: the ends, the route planned and its error, if any. */
    route: () => state.route.snapshot(),
    /** The rooms the page shows (as read from the worker). */
    get rooms() {
      return state.rooms.rooms;
    },
    /** The edits the page shows as in force. */
    get edits() {
      return state.edits;
    },
    /** The selected room ({ x, y, room }) or null. */
    get selected() {
      return state.selected;
    },
    /** Their type marginals and room labels (roomTypesJson, roomLabels), as read. */
    get roomDetails() {
      return state.rooms.fresh;
    },
    /** The map on the page (a wasm Map). */
    get map() {
      return state.map;
    },
    // What the page waits for, whether it is idle, and its numbers: below.
    waits,
    idle,
    snapshot,
  };
}

/** A rooms feed's waits, for `waits()`. */
function feedWaits(f) {
  return { inFlight: f.inFlight, again: f.again, generation: f.generation, readAt: f.readAt };
}

/** What the page waits for (for tests that time out waiting for idle()). */
function waits() {
  const w = state.weak;
  return {
    running: state.running,
    dataRunning: document.documentElement.dataset.running,
    inFlight: state.inFlight,
    redrawPending: state.redrawPending,
    picture: Boolean(state.picture),
    busy: state.chain.busy,
    generation: state.stats?.generation,
    iteration: state.stats?.iteration,
    rooms: feedWaits(state.rooms),
    weak: w && { iteration: w.stats?.iteration, generation: w.stats?.generation, inFlight: w.inFlight, redrawPending: w.redrawPending, picture: Boolean(w.picture), busy: w.chain.busy, rooms: feedWaits(w.rooms) },
  };
}

/** Whether the chain is paused and its latest state (and the weak prior's, if any) drawn. */
function isIdle() {
  const paused = !state.running && document.documentElement.dataset.running === 'false';
  const w = state.weak;
  const weakIdle = !w || (w.stats && w.stats.iteration === state.stats?.iteration && !w.inFlight && !w.redrawPending && !w.picture && w.chain.busy === 0 && w.rooms.current(w.stats));
  return paused && !state.inFlight && !state.redrawPending && !state.picture && state.chain.busy === 0 && state.rooms.current(state.stats) && weakIdle;
}

/** Resolves once the page has drawn the chain's latest state and waits for nothing. */
function idle() {
  return new Promise((resolve) => {
    const check = () => {
      if (isIdle()) resolve();
      else requestAnimationFrame(check);
    };
    requestAnimationFrame(check);
  });
}

/** The page's numbers and settings, as plain data. */
function snapshot() {
  const m = state.stats;
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
    settledAt: m?.settledAt ?? null,
    improvedAt: m?.improvedAt ?? null,
    settleWindow: m?.settleWindow ?? 0,
    wings: m?.wings ?? null,
    wingsDone: m?.wingsDone ?? 0,
    wingsPredictionRate: m?.wingsPredictionRate ?? null,
    stopWhenSettled: ui.stopSettled.checked,
    show: state.show,
    cloud: state.cloud,
    scale: state.scale,
    drawScale: state.drawScale,
    view: state.viewport.view.state(),
    room: state.hover.id,
    roomPinned: state.hover.pinned,
    ipf: state.ipf,
    drawMs: state.drawMs,
    painting: state.painting,
    error: ui.message.hidden ? null : ui.messageText.textContent,
  };
}
