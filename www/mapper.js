// The live mapper page: a data-driven MCMC chain explains an occupancy map with a semantic
// floor plan while you watch. The chain, the pictures and the exports are the library's
// (pkg/ksmcmc.js; the rooms and exports pkg/ksmcmc_plan.js, which the worker loads when the
// best world first has units). The chain runs in a Web Worker (lib/chain-worker.js), so that
// no step of it, however long, blocks a frame of the page; the page draws the pictures the
// worker sends, at most one per animation frame, and asks for the next one when it has drawn
// the last.

import init, { Map as OccMap, chainConfigDefaults, drawToCanvas, version } from './pkg/ksmcmc.js';
import { TOOLS, MAX_BRUSH, brushOffsets, stamp, strokeTo, cellAt } from './lib/paint.js';
import { parseSeed, onDroppedFiles, readPickedMap } from './lib/files.js';
import { SampleList, fetchSampleFile, fetchSampleMap } from './lib/samples.js';
import { buildMap } from './lib/map-source.js';
import { drawPlot, formatNumber, parseIterationsPerFrame } from './lib/plot.js';
import { messages } from './lib/messages.js';
import { download } from './lib/download.js';
import { RemoteChain } from './lib/remote-chain.js';
import { RouteView } from './lib/route-view.js';
import { describeEdit, parseEdits } from './lib/edits.js';
import { Viewport, detailScale } from './lib/viewport.js';
import { RoomIndex, fillRoomInfo } from './lib/room-info.js';

/** Step runs this many iterations when the speed is `auto`. */
const AUTO_STEP = 500;
/** The most pixels per cell the page draws for the whole map (more only costs time per frame). */
const MAX_SCALE = 3;
/**
 * The largest picture the worker draws when zoomed in, pixels: it draws the whole map, so the
 * detail of a large map's zoom is limited by the time a picture takes.
 */
const MAX_PICTURE_PIXELS = 6_000_000;
/** While the chain runs, the rooms are read at most this often (the worker computes them). */
const ROOMS_EVERY_MS = 2000;
/** The weak prior's chain catches up with the main one in steps of at most this many iterations. */
const WEAK_STEP_MAX = 20000;
/** The room types, in the order the page lists them. */
const ROOM_TYPES = ['room', 'corridor', 'hall', 'other', 'unknown'];

const $ = (id) => document.getElementById(id);
const ui = {
  message: $('message'), messageText: $('message-text'), messageClose: $('message-close'),
  status: $('status'), version: $('version'),
  run: $('run'), step: $('step'), reset: $('reset'), seed: $('seed'), ipf: $('ipf'),
  config: $('config'), configDefaults: $('config-defaults'), knowledge: $('knowledge'), stopSettled: $('stop-settled'),
  sampleForm: $('sample-form'), sample: $('sample'), sampleLoad: $('sample-load'), sampleHint: $('sample-hint'),
  file: $('file'), classify: $('classify'),
  paint: $('paint'), brush: $('brush'), brushValue: $('brush-value'),
  blankForm: $('blank-form'), blankWidth: $('blank-width'), blankHeight: $('blank-height'), blankCreate: $('blank-create'),
  showReference: $('show-reference'), cloud: $('cloud'), labels: $('labels'),
  worldFile: $('world-file'), truth: $('truth'), referenceClear: $('reference-clear'),
  stage: $('stage'), canvas: $('map'), graph: $('graph'), mapName: $('map-name'), roomInfo: $('room-info'), zoomBar: $('zoom-bar'),
  compare: $('compare'), mainCaption: $('main-caption'), mainTitle: $('main-title'), mainSide: $('main-side'),
  weakFigure: $('weak-figure'), weakCanvas: $('weak-map'), weakSide: $('weak-side'),
  rooms: $('rooms').tBodies[0], roomsSummary: $('rooms-summary'),
  plotLp: $('plot-lp'), plotAcc: $('plot-acc'), plotLpValue: $('plot-lp-value'), plotAccValue: $('plot-acc-value'),
  stats: $('stats'),
  view3d: {
    toggle: $('view-3d'), panel: $('view3d-panel'), form: $('view3d-form'), canvas: $('view3d'),
    wall: $('wall-height'), door: $('door-height'), reset: $('view3d-reset'), status: $('view3d-status'),
  },
  route: {
    toggle: $('route-mode'), form: $('route-form'), from: $('route-from'), to: $('route-to'), plan: $('route-plan'),
    layer: $('route-layer'), summary: $('route-summary'), rooms: $('route-rooms'), doors: $('route-doors'),
  },
  stat: {
    iteration: $('stat-iteration'), rate: $('stat-rate'), lp: $('stat-lp'), best: $('stat-best'), acc: $('stat-acc'),
    units: $('stat-units'), doors: $('stat-doors'), rooms: $('stat-rooms'), k: $('stat-k'), rotation: $('stat-rotation'), setup: $('stat-setup'),
    settled: $('stat-settled'),
  },
  exports: {
    world: $('export-world'), labels: $('export-labels'), png: $('export-png'), graph: $('export-graph'),
    report: $('export-report'), glb: $('export-glb'),
    geojson: $('export-geojson'), svg: $('export-svg'),
  },
  georef: $('georef'),
  edit: {
    selection: $('edit-selection'), type: $('edit-type'), typeApply: $('edit-type-apply'),
    nameForm: $('edit-name-form'), name: $('edit-name'), nameApply: $('edit-name-apply'),
    merge: $('edit-merge'), split: $('edit-split'), undo: $('edit-undo'), clear: $('edit-clear'),
    exportEdits: $('edit-export'), importEdits: $('edit-import'), list: $('edit-list'),
  },
};

const { showError, clearError, say, attempt, loadWasm } = messages(ui);

const state = {
  ready: false,
  /** The map being explained (a wasm Map on this thread: for painting and its size). */
  map: null,
  /** How the worker makes the map (what `load` was given): the weak prior's chain loads it too. */
  source: null,
  /** The best world's rooms, read from the worker (a RoomsFeed, made in main()). */
  rooms: null,
  /** Route mode: the ends picked and the route planned (a RouteView, made in main()). */
  route: null,
  /**
   * The 3D view: whether it is open, the View3d (made when first opened, when three.js
   * loads), the request on its way (a reply to an older one is dropped), its last error.
   */
  view3d: { open: false, view: null, token: 0, shown: 0, error: null },
  /** The weak prior's chain beside this one (Compare with the weak prior), or null. */
  weak: null,
  /** What the chain was started with (chainArgs()). */
  args: null,
  name: 'map',
  label: '',
  sample: null,
  /** The sample list, with the description of the picked sample. */
  sampleList: new SampleList(ui.sample, ui.sampleHint, '(an opened or painted map)'),
  /** The chain in its worker, and its numbers as last reported (null before the first map). */
  chain: null,
  stats: null,
  running: false,
  raf: 0,
  /** A picture is wanted (the view or the chain changed), one is on its way, one waits to be drawn. */
  redrawPending: false,
  inFlight: false,
  picture: null,
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
  /** Pictures drawn while the chain ran, and when the rate was last measured: for iterations/s. */
  frames: 0,
  rate: { iteration: 0, time: 0, perSecond: 0 },
  /** Milliseconds drawing a picture takes on this thread (a running average). */
  drawMs: 0,
  scale: 1,
  /** Zoom and pan of the map (a Viewport, made in wire()); the weak prior's picture follows it. */
  viewport: null,
  /** Pixels per cell the worker draws at: `scale` at zoom 1, more when zoomed in. */
  drawScale: 1,
  /** The pictures last drawn, kept to draw them again when the view moves. */
  shown: null,
  weakShown: null,
  /** The painted cells while a stroke goes on (a canvas, one pixel per cell). */
  paintCanvas: null,
  /** The best world's rooms for pointing at (a RoomIndex), and the room shown: hovered, focused or pinned. */
  roomIndex: null,
  hover: { id: 0, pinned: false, anchor: null, mask: null },
  /** Where the mouse is over the map (client position), or null; whether the Rooms table is in use. */
  pointer: null,
  tableInUse: false,
  /** Painting: cell codes as loaded and as painted, the stroke's last cell. */
  painting: false,
  tool: 'occupied',
  brush: 3,
  offsets: brushOffsets(3),
  base: null,
  codes: null,
  strokeAt: null,
  strokeUndo: null,
  /** The edits in force (as the worker's `editsJson` last said), the selected room's cell and id. */
  edits: [],
  selected: null,
  /** 'merge' or 'split' while the next click on the map finishes one; a split's first point. */
  editMode: null,
  splitFrom: null,
  splitDrag: false,
};

// ---------------------------------------------------------------- the chain

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
function withoutKnowledge(text) {
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

// ---------------------------------------------------------------- rooms

/**
 * The best world's rooms of one chain, read from its worker (`roomsJson`, computed there):
 * never more than one request on its way; one asked for meanwhile follows when it is back.
 */
class RoomsFeed {
  /**
   * @param {() => RemoteChain} chain  the chain's worker
   * @param {(rooms: object[] | null, details: object | null) => void} show  called with the
   *   rooms (null: none read yet) and their details, if wanted and read for these rooms
   */
  constructor(chain, show) {
    this.chain = chain;
    this.show = show;
    /**
     * Whether the rooms' details are wanted: their type marginals and the room of every cell
     * (for pointing at rooms). Read only while wanted: the labels are two bytes per cell, and
     * reading them every 2 s on a large map makes garbage enough for a long collection.
     */
    this.details = false;
    this.generation = -1;
    this.rooms = null;
    /** { types, labels } of the rooms, and the rooms' text they were read with. */
    this.extra = null;
    this.extraText = null;
    /** The rooms' JSON text as last read. */
    this.text = null;
    this.inFlight = false;
    this.again = false;
    this.at = 0;
    this.readAt = -1;
  }

  /** A new chain: forget the old one's rooms and read the new one's. */
  restart(generation, iteration) {
    this.generation = generation;
    this.rooms = null;
    this.extra = null;
    this.extraText = null;
    this.text = null;
    this.readAt = iteration;
    this.show(null);
    this.request();
  }

  /**
   * Keeps the rooms up to date with the chain whose numbers are `stats`: every ROOMS_EVERY_MS
   * while it runs, and once more when it has stopped (paused, settled or stepped).
   */
  follow(stats, running, now) {
    if (!stats || stats.generation !== this.generation) return;
    if (running) {
      if (!this.inFlight && now - this.at >= ROOMS_EVERY_MS) {
        this.readAt = stats.iteration;
        this.request();
      }
    } else if (this.readAt !== stats.iteration) {
      this.readAt = stats.iteration;
      this.request();
    }
  }

  /** Details wanted or not; wanted and not read for the rooms shown, they are read now. */
  want(on) {
    this.details = on;
    if (on && this.generation >= 0 && (this.extraText === null || this.extraText !== this.text)) this.request();
  }

  /** The details, if they are those of the rooms shown. */
  get fresh() {
    return this.extra && this.extraText === this.text ? this.extra : null;
  }

  /** Whether the rooms shown are those of the chain at `stats`, with nothing on its way. */
  current(stats) {
    return !this.inFlight && !this.again && stats?.generation === this.generation && this.readAt === stats.iteration;
  }

  request() {
    if (this.inFlight) {
      this.again = true;
      return;
    }
    this.inFlight = true;
    this.again = false;
    this.at = performance.now();
    const generation = this.generation;
    this.chain()
      .call('rooms', { details: this.details, known: this.rooms ? this.text : null, knownDetails: this.extra ? this.extraText : null })
      .then(
        (reply) => {
          if (generation !== this.generation) {
            this.again = true;
            return;
          }
          // The same rooms as last time (the best world has not changed): nothing to redo.
          if (reply.same) return;
          this.text = reply.text;
          this.rooms = JSON.parse(reply.text);
          if (reply.types !== null) {
            this.extra = { types: JSON.parse(reply.types), labels: reply.labels };
            this.extraText = reply.text;
          }
          this.show(this.rooms, this.fresh);
        },
        (err) => showError(err),
      )
      .finally(() => {
        this.inFlight = false;
        if (this.again) this.request();
      });
  }

}

/** "3 rooms, 1 corridor" for a rooms list. */
function roomsByType(rooms) {
  const counts = new Map();
  for (const r of rooms) counts.set(r.type, (counts.get(r.type) ?? 0) + 1);
  const order = (t) => (ROOM_TYPES.indexOf(t) + ROOM_TYPES.length + 1) % (ROOM_TYPES.length + 1);
  return [...counts].sort(([a], [b]) => order(a) - order(b) || a.localeCompare(b)).map(([t, n]) => `${n} ${t}`).join(', ');
}

function cell(tr, text) {
  const td = document.createElement('td');
  td.textContent = text;
  tr.append(td);
}

/**
 * The rooms table and the rooms count of the main chain, and the rooms the map points at
 * (`details`: their type marginals and the room of every cell).
 */
function showRooms(rooms, details) {
  ui.stat.rooms.textContent = rooms ? String(rooms.length) : '–';
  ui.stats.dataset.rooms = rooms ? String(rooms.length) : '';
  const m = state.map;
  state.roomIndex = rooms && details && m ? new RoomIndex(rooms, details.types, details.labels, m.width, m.height) : null;
  // The row in focus is remade: focus moves to its successor, so that the keyboard stays put.
  const focused = ui.rooms.contains(document.activeElement) ? document.activeElement.dataset.room : null;
  ui.rooms.replaceChildren(
    ...(rooms ?? []).map((r) => {
      const tr = document.createElement('tr');
      tr.dataset.room = String(r.id);
      tr.dataset.type = r.type;
      tr.tabIndex = 0;
      tr.setAttribute('aria-selected', String(state.selected?.room === r.id));
      cell(tr, r.name ? `${r.id} ${r.name}` : String(r.id));
      cell(tr, r.type);
      cell(tr, formatNumber(r.area_m2, 1));
      cell(tr, r.units.join(', '));
      cell(tr, r.opens_to.length ? r.opens_to.join(', ') : '–');
      return tr;
    }),
  );
  if (focused) ui.rooms.querySelector(`tr[data-room="${focused}"]`)?.focus({ preventScroll: true });
  refreshHover();
  // The details came while the pointer or the focus waited for them.
  if (!state.hover.id && state.roomIndex) {
    if (ui.rooms.contains(document.activeElement)) pointRoom(document.activeElement.closest('tr'), true);
    else if (state.pointer && !state.painting) setHover(roomAt(...state.viewport.contentAt(state.pointer, ui.canvas)), state.pointer);
  }
  ui.roomsSummary.textContent = !rooms
    ? 'Reading the best world\'s rooms…'
    : rooms.length === 0
      ? 'The best world has no rooms yet.'
      : `The best world's ${rooms.length} room${rooms.length === 1 ? '' : 's'}: ${roomsByType(rooms)} (units merged where no wall parts them, as in world.json). Click a row to select the room.`;
  updateSides();
  // A route and the 3D view follow the best world.
  if (rooms) {
    state.route?.refresh();
    refresh3d();
  }
  if (rooms && state.selected) refreshSelection();
}

/**
 * Takes on the chain's numbers from a reply, unless a later reply's are already here: the
 * worker numbers them in the order it made them (a picture asked for before a change may
 * arrive after the change's reply).
 */
function takeStats(stats) {
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
 * Shows a new map and starts a chain on it; `source` says how the worker makes the same map.
 * If the chain cannot start, nothing changes (and `map` is freed).
 */
async function setMap(map, source, { name, label, sample = null, uploaded = false }) {
  let reply;
  let args;
  try {
    args = chainArgs();
    reply = await state.chain.call('load', { source, ...args });
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

function play() {
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

function pause() {
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

function toggle() {
  if (state.running) pause();
  else play();
}

/** The worker paused the chain because it settled. */
function chainSettled(stats) {
  takeStats(stats);
  stopped();
  say(
    `Settled at iteration ${formatNumber(stats.settledAt)}: the best log posterior improved by less than 0.01 % ` +
      `over the last ${formatNumber(stats.settleWindow)} iterations. Start runs on.`,
  );
  requestRedraw();
}

/**
 * The worker explains the wings of a building whose walls follow several directions, a chain
 * per wing once the chain has stopped (`stats.wings`), or has explained them (`wingsDone`):
 * the best world's rooms and picture are then theirs.
 */
function chainWings(stats) {
  takeStats(stats);
  const w = stats.wings;
  if (w) {
    say(
      `The walls follow ${w.of} directions: explaining wing ${w.wing} of ${w.of} in its own direction ` +
        `(${formatNumber(w.rotationDeg, 1)}°), ${formatNumber(w.target)} iterations as the first chain ran.`,
    );
  } else if (stats.wingsDone > 0) {
    say(`The ${stats.wingsDone} wings were explained each in its own direction: the best world's units lie at their angles.`);
    state.rooms.request();
    requestRedraw();
  }
}

/** The worker stopped the chain because a step failed. */
function chainFailed(message, stats) {
  if (stats) takeStats(stats);
  stopped();
  showError(new Error(message));
  requestRedraw();
}

/** What the worker draws: the view and the pixel sizes of the two canvases. */
function view() {
  const s = state.stats;
  const dpr = globalThis.devicePixelRatio || 1;
  const gw = Math.max(80, Math.round(ui.graph.clientWidth * dpr) || 320);
  const gh = Math.max(60, Math.round(gw * Math.min(1, Math.max(0.45, s.height / s.width))));
  return {
    generation: s.generation,
    show: state.show,
    cloud: state.cloud,
    labels: state.labels,
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

function schedule() {
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

// ---------------------------------------------------------------- the weak prior beside it

/** Turns the comparison with the weak prior on or off (a second chain in its own worker). */
function setCompare(on) {
  ui.compare.checked = on;
  if (on && !state.weak) {
    const weak = {
      chain: new RemoteChain((message) => showError(new Error(`The weak prior's chain: ${message}`)), () => {}),
      stats: null,
      picture: null,
      inFlight: false,
      redrawPending: false,
      /** Counts the weak chain's restarts: replies about an older one are dropped. */
      token: 0,
    };
    weak.rooms = new RoomsFeed(() => weak.chain, () => updateSides());
    state.weak = weak;
    startWeak();
  } else if (!on && state.weak) {
    state.weak.chain.worker.terminate();
    state.weak.picture?.close();
    state.weak = null;
    state.weakShown?.close();
    state.weakShown = null;
  }
  ui.weakFigure.hidden = !on;
  ui.mainCaption.hidden = !on;
  // The two pictures take the width of the page; the scene graph and the plots go below.
  ui.stage.closest('.mapper-grid').classList.toggle('comparing', on);
  fit();
  updateSides();
}

/**
 * Starts the weak prior's chain over on the main chain's map with its seed and settings, but
 * knowledge supervision off; it then follows the main chain's iterations.
 */
async function startWeak() {
  const weak = state.weak;
  if (!weak || !state.source || !state.args) return;
  const token = ++weak.token;
  weak.stats = null;
  weak.picture?.close();
  weak.picture = null;
  const { seed, config } = state.args;
  try {
    const { stats } = await weak.chain.call('load', { source: state.source, config: withoutKnowledge(config ?? '') || undefined, seed });
    if (state.weak !== weak || token !== weak.token) return;
    weak.stats = stats;
    weak.rooms.restart(stats.generation, stats.iteration);
    weak.redrawPending = true;
    schedule();
  } catch (err) {
    if (state.weak === weak && token === weak.token) showError(new Error(`The weak prior's chain did not start: ${err.message}`));
  }
}

/** What the weak prior's worker draws: the main view (a reference world it does not have: its best). */
function weakView(generation) {
  return {
    generation,
    show: state.show === 'reference' ? 'best' : state.show,
    cloud: state.cloud,
    labels: state.labels,
    scale: state.drawScale,
    graphWidth: 80,
    graphHeight: 60,
    graphShow: 'best',
    traceFrom: Infinity,
  };
}

/**
 * Steps the weak prior's chain towards the main chain's iteration (at most WEAK_STEP_MAX at a
 * time) and asks for its picture; one request at a time, in its own worker, so the page waits
 * for nothing.
 */
function advanceWeak() {
  const weak = state.weak;
  if (!weak || !weak.stats || weak.inFlight || !state.stats) return;
  const behind = state.stats.iteration - weak.stats.iteration;
  if (behind <= 0 && !weak.redrawPending) return;
  weak.inFlight = true;
  weak.redrawPending = false;
  const token = weak.token;
  const steps = behind > 0 ? weak.chain.call('step', { n: Math.min(WEAK_STEP_MAX, behind) }) : null;
  const picture = weak.chain.call('frame', weakView(weak.stats.generation));
  Promise.all([steps, picture]).then(
    ([, result]) => {
      weak.inFlight = false;
      result?.graph.close();
      if (state.weak !== weak || token !== weak.token || !result) {
        result?.picture.close();
      } else {
        weak.picture?.close();
        weak.picture = result.picture;
        weak.stats = result.stats;
      }
      schedule();
    },
    (err) => {
      weak.inFlight = false;
      if (state.weak === weak && token === weak.token) showError(new Error(`The weak prior's chain: ${err.message}`));
    },
  );
}

/** A side's summary: K(W,M), units, rooms and rooms by type. */
function sideText(stats, rooms) {
  if (!stats) return 'starting…';
  const parts = [`K(W,M) ${formatNumber(stats.bestPredictionRate, 4)}`, `${stats.bestUnits} units`];
  parts.push(rooms ? `${rooms.length} rooms${rooms.length ? ` (${roomsByType(rooms)})` : ''}` : 'rooms …');
  return `iteration ${formatNumber(stats.iteration)} · ${parts.join(' · ')}`;
}

/** The captions of the two pictures when the weak prior is shown beside the main chain. */
function updateSides() {
  const weak = state.weak;
  if (!weak) return;
  ui.mainTitle.textContent = state.args?.knowledge === false ? 'This chain (knowledge supervision off)' : 'Knowledge';
  ui.mainSide.textContent = sideText(state.stats, state.rooms.rooms);
  ui.weakSide.textContent = sideText(weak.stats, weak.rooms.rooms);
  ui.weakCanvas.setAttribute('aria-label', `The weak prior's chain: ${ui.weakSide.textContent}`);
}

function step() {
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
function reset() {
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

// ---------------------------------------------------------------- drawing

/** Draws at the next animation frame (once, however often it is asked). */
function requestRedraw() {
  state.redrawPending = true;
  if (state.weak) state.weak.redrawPending = true;
  schedule();
}

function drawBitmap(canvas, bitmap) {
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
function showPicture(picture) {
  state.shown?.close();
  state.shown = picture;
  paintMain();
}

/** Draws the main picture (or, during a stroke, the painted cells) through the view. */
function paintMain() {
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

function paintWeak() {
  if (state.weak && state.weakShown) state.viewport.draw(ui.weakCanvas, state.weakShown);
}

/**
 * The view moved: both pictures are drawn again at once from what was last received, and a
 * sharper one is asked for if the zoom needs more pixels per cell.
 */
function viewChanged() {
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

/**
 * Sizes the canvas on screen to fit the stage, and picks the drawing scale: enough pixels per
 * cell for the screen's resolution (at most 3), so that the picture is shrunk smoothly rather
 * than blown up, except for small maps on large screens.
 */
function fit() {
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

// ---------------------------------------------------------------- maps

async function loadSample(name) {
  state.sampleList.find(name);
  const source = await fetchSampleMap(name);
  await setMap(buildMap(source), source, { name, label: name, sample: name });
}

/** Loads a map from the picked files: one image, or a map.yaml with the image it names. */
async function openFiles(fileList) {
  const { source, name, label } = await readPickedMap(fileList, ui.classify.value);
  await setMap(buildMap(source), source, { name, label, uploaded: true });
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

// ---------------------------------------------------------------- painting

function setPainting(on) {
  if (on) setRouting(false);
  state.painting = on;
  ui.paint.checked = on;
  ui.canvas.classList.toggle('painting', on);
  if (on) {
    pause();
    say('Painting: drag on the map. After each stroke the chain goes on from its world on the painted map; Reset starts over.');
  }
}

// ---------------------------------------------------------------- 3D view

/** The heights in the 3D view's form, for `worldGlb`. */
function heights() {
  return { wallHeight: Number(ui.view3d.wall.value), doorHeight: Number(ui.view3d.door.value) };
}

/** Opens or closes the 3D view; opening it the first time loads three.js. */
async function setView3d(on) {
  const v = state.view3d;
  if (on === v.open) return;
  v.open = on;
  ui.view3d.toggle.setAttribute('aria-pressed', String(on));
  ui.view3d.panel.hidden = !on;
  if (!on) return;
  if (!v.view) {
    ui.view3d.status.textContent = 'Loading the 3D viewer…';
    try {
      const { View3d } = await import('./lib/view3d.js');
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
async function refresh3d() {
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
function setRouting(on) {
  if (!state.route || on === state.route.active) return;
  if (on && state.painting) setPainting(false);
  // The route's layer is drawn at the whole map's scale: route mode shows the whole map.
  if (on) state.viewport?.reset?.();
  state.route.setActive(on);
  state.route.show();
  say(on ? 'Route mode: click the start, then the goal on the map. Esc leaves it.' : 'Left route mode.');
}

/** The cell under a pointer event, through the zoom and pan. */
function cellFromEvent(e) {
  const [u, v] = state.viewport.contentAt(e, ui.canvas);
  return cellAt(u, v, { width: 1, height: 1 }, state.map.width, state.map.height);
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
function abortStroke() {
  if (!state.strokeAt) return;
  state.strokeAt = null;
  state.codes = state.strokeUndo ?? state.base.slice();
  paintMain();
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

function onPointerMove(e) {
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
async function onPointerUp(e) {
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

function setBrush(size) {
  const s = Math.min(MAX_BRUSH, Math.max(1, Math.round(Number(size)) || 1));
  state.brush = s;
  state.offsets = brushOffsets(s);
  ui.brush.value = String(s);
  ui.brushValue.textContent = String(s);
}

// ---------------------------------------------------------------- pointing at rooms

/**
 * Shows room `id` (0: none) of the best world: its cells highlighted on the map, and its type,
 * area, doors, units and type marginals in the info box, beside `anchor` (a pointer's client
 * position) or, without one, beside the room. A `pinned` room (clicked or tapped) stays when
 * the pointer leaves; Escape, or a click outside any room, hides it.
 */
function setHover(id, anchor = null, pinned = false) {
  const h = state.hover;
  const room = id ? state.roomIndex?.rooms.get(id) : null;
  const shown = room ? id : 0;
  h.pinned = Boolean(shown) && pinned;
  h.anchor = anchor;
  if (shown !== h.id) {
    h.id = shown;
    h.mask = shown ? state.roomIndex.mask(shown) : null;
    paintMain();
    if (shown) fillRoomInfo(ui.roomInfo, room, state.roomIndex.types.get(shown));
  }
  ui.roomInfo.hidden = !shown;
  ui.roomInfo.dataset.pinned = String(h.pinned);
  if (!shown) delete ui.roomInfo.dataset.room;
  placeRoomInfo();
}

/** The rooms were read again: the room shown is shown as it is now (hidden if it is gone). */
function refreshHover() {
  const h = state.hover;
  if (!h.id) return;
  const id = h.id;
  h.id = 0;
  h.mask = null;
  setHover(id, h.anchor, h.pinned);
}

/** Puts the info box beside its anchor (or its room), inside the stage. */
function placeRoomInfo() {
  const box = ui.roomInfo;
  const h = state.hover;
  if (box.hidden || !h.id) return;
  const stage = ui.stage.getBoundingClientRect();
  let x;
  let y;
  if (h.anchor) {
    x = h.anchor.clientX - stage.left + 16;
    y = h.anchor.clientY - stage.top + 16;
  } else {
    const b = state.roomIndex.box(h.id);
    const m = state.map;
    const c = ui.canvas.getBoundingClientRect();
    const [fx, fy] = b ? state.viewport.view.toElement(b.cx / m.width, b.cy / m.height) : [0.5, 0.5];
    x = c.left - stage.left + Math.min(1, Math.max(0, fx)) * c.width + 12;
    y = c.top - stage.top + Math.min(1, Math.max(0, fy)) * c.height + 12;
  }
  const w = box.offsetWidth;
  const hh = box.offsetHeight;
  if (x + w > stage.width) x = Math.max(0, x - w - 32);
  if (y + hh > stage.height) y = Math.max(0, stage.height - hh);
  box.style.left = `${Math.round(x)}px`;
  box.style.top = `${Math.round(y)}px`;
}

/** The room under the content point (u, v) of the map, or 0. */
function roomAt(u, v) {
  return state.roomIndex ? state.roomIndex.atContent(u, v) : 0;
}

/**
 * The rooms' details (type marginals, the room of every cell) are read from the worker only
 * while someone points at rooms: the mouse on the map, the Rooms table in use, a room pinned.
 */
function wantRoomDetails() {
  state.rooms?.want(Boolean(state.pointer || state.tableInUse || state.hover.pinned));
}

/** A mouse or pen over the map shows the room under it. */
function onHover(e) {
  if (e.pointerType !== 'mouse' && e.pointerType !== 'pen') return;
  const wanted = !state.pointer;
  state.pointer = { clientX: e.clientX, clientY: e.clientY };
  if (wanted) wantRoomDetails();
  if (e.buttons || state.painting || state.hover.pinned) return;
  setHover(roomAt(...state.viewport.contentAt(e, ui.canvas)), state.pointer);
}

function onLeave() {
  state.pointer = null;
  if (!state.hover.pinned) setHover(0);
  wantRoomDetails();
}

/** A click or tap that did not drag: pins the room there, or unpins. */
function onTap(e, u, v) {
  if (state.painting || e.currentTarget !== ui.canvas) return;
  const id = roomAt(u, v);
  if (!id || (state.hover.pinned && state.hover.id === id)) setHover(0);
  else setHover(id, { clientX: e.clientX, clientY: e.clientY }, true);
  wantRoomDetails();
}

/** A row of the Rooms table in focus (or under the mouse): its room on the map, in view. */
function pointRoom(tr, reveal) {
  const id = Number(tr?.dataset.room);
  // The mouse passing over the table leaves a pinned room; the keyboard moves on from it.
  if (!id || (!reveal && state.hover.pinned)) return;
  setHover(id);
  const b = reveal && state.roomIndex?.box(id);
  if (b) state.viewport.reveal(b.cx / state.map.width, b.cy / state.map.height);
}

// ---------------------------------------------------------------- view and reference

function setShow(show) {
  if (show === 'reference' && !state.stats?.hasReference) return;
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
  const has = Boolean(state.stats?.hasReference);
  ui.showReference.disabled = !has;
  ui.referenceClear.disabled = !has;
  if (!has && state.show === 'reference') setShow('best');
}

async function setReference(text, name) {
  takeStats(await state.chain.call('setReference', { json: text }));
  state.referenceJson = text;
  state.referenceName = name;
  updateReferenceControls();
  setShow('reference');
  clearError();
  say(`Showing ${name} as the reference world.`);
}

// ---------------------------------------------------------------- exports

/** Calls one of the chain's export methods in the worker. */
function invoke(name, ...args) {
  return state.chain.call('invoke', { name, args });
}

function save(name, data, type) {
  download(name, data, type);
  say(`Saved ${name}.`);
}

// ---------------------------------------------------------------- edits

/** The edits in force as the worker holds them (Reset keeps them, a new map drops them). */
function syncEdits() {
  invoke('editsJson').then((text) => showEdits(JSON.parse(text)), showError);
}

function showEdits(list) {
  state.edits = list;
  ui.edit.list.replaceChildren(
    ...list.map((e) => {
      const li = document.createElement('li');
      li.textContent = describeEdit(e);
      return li;
    }),
  );
  ui.edit.list.dataset.count = String(list.length);
  updateEditControls();
}

function updateEditControls() {
  const ready = Boolean(state.stats);
  const selected = ready && Boolean(state.selected?.room);
  for (const c of [ui.edit.type, ui.edit.typeApply, ui.edit.name, ui.edit.nameApply, ui.edit.merge, ui.edit.split]) c.disabled = !selected;
  ui.edit.undo.disabled = ui.edit.clear.disabled = !ready || state.edits.length === 0;
  ui.edit.exportEdits.disabled = ui.edit.importEdits.disabled = !ready;
  ui.edit.merge.setAttribute('aria-pressed', String(state.editMode === 'merge'));
  ui.edit.split.setAttribute('aria-pressed', String(state.editMode === 'split'));
}

/**
 * Sends the whole list to the worker (the chain goes on from its current world with it) and
 * shows what the worker holds; a list it refuses changes nothing and shows why.
 */
async function sendEdits(list, done) {
  try {
    await invoke('setEdits', JSON.stringify(list));
    showEdits(JSON.parse(await invoke('editsJson')));
    state.rooms.request();
    requestRedraw();
    clearError();
    if (done) say(done);
  } catch (err) {
    showError(err);
  }
}

function addEdit(edit) {
  return sendEdits([...state.edits, edit], `Edit: ${describeEdit(edit)}.`);
}

function undoEdit() {
  if (!state.stats || state.edits.length === 0) return;
  const last = state.edits[state.edits.length - 1];
  sendEdits(state.edits.slice(0, -1), `Undone: ${describeEdit(last)}.`);
}

/** Selects the best world's room at map cell (x, y) (or, with `id`, that room); null: none. */
async function select(at) {
  setEditMode(null);
  if (!at) {
    state.selected = null;
    showSelection();
    return;
  }
  try {
    state.selected = await state.chain.call('roomAt', at);
  } catch (err) {
    showError(err);
    state.selected = null;
  }
  showSelection();
}

/** The selected cell's room again (the best world changed). */
function refreshSelection() {
  const { x, y } = state.selected;
  state.chain.call('roomAt', { x, y }).then((s) => {
    if (state.selected?.x === x && state.selected?.y === y && s) {
      state.selected = s;
      showSelection();
    }
  }, showError);
}

function showSelection() {
  const s = state.selected;
  const room = s?.room ? state.rooms.rooms?.find((r) => r.id === s.room) : null;
  ui.edit.selection.textContent = !s
    ? 'Click a room on the map, or a row of the Rooms table, to select it.'
    : !s.room
      ? `No room at (${s.x}, ${s.y}) in the best world.`
      : `Selected: room ${s.room}${room ? ` (${room.type}${room.name ? `, “${room.name}”` : ''})` : ''} at (${s.x}, ${s.y}).`;
  ui.edit.selection.dataset.room = s?.room ? String(s.room) : '';
  if (room && EDIT_TYPE_SET.has(room.type)) ui.edit.type.value = room.type;
  for (const tr of ui.rooms.rows) tr.setAttribute('aria-selected', String(s?.room === Number(tr.dataset.room)));
  drawOverlay();
  updateEditControls();
}

const EDIT_TYPE_SET = new Set(['room', 'corridor', 'hall', 'other']);

function setEditMode(mode) {
  state.editMode = mode;
  state.splitFrom = null;
  state.splitDrag = false;
  drawOverlay();
  ui.canvas.classList.toggle('editing', Boolean(mode));
  if (mode === 'merge') say('Merge: click the room to merge with on the map or in the Rooms table (Esc cancels).');
  if (mode === 'split') say('Split: drag a line across the room on the map, or click its two ends (Esc cancels).');
  updateEditControls();
}

/**
 * What the edits draw over the map (an SVG in map cells): a ring at the selected room's cell,
 * and a split's line while it is drawn (from `state.splitFrom` to `to`).
 */
function drawOverlay(to = null) {
  let svg = ui.canvas.parentElement.querySelector('.edit-line');
  const sel = state.selected?.room ? state.selected : null;
  if (!state.map || (!sel && !state.splitFrom)) {
    svg?.remove();
    return;
  }
  const { width, height } = state.map;
  if (!svg) {
    svg = document.createElementNS('http://www.w3.org/2000/svg', 'svg');
    svg.setAttribute('class', 'edit-line');
    svg.setAttribute('aria-hidden', 'true');
    svg.setAttribute('preserveAspectRatio', 'none');
    svg.innerHTML = '<circle class="selected" vector-effect="non-scaling-stroke"/><circle class="from" vector-effect="non-scaling-stroke"/><line vector-effect="non-scaling-stroke"/>';
    ui.canvas.parentElement.append(svg);
  }
  svg.setAttribute('viewBox', `0 0 ${width} ${height}`);
  const cv = ui.canvas;
  Object.assign(svg.style, { left: `${cv.offsetLeft}px`, top: `${cv.offsetTop}px`, width: `${cv.clientWidth}px`, height: `${cv.clientHeight}px` });
  const [ring, from, line] = svg.children;
  const r = Math.max(2, Math.min(width, height) / 40);
  const put = (el, attrs) => {
    el.toggleAttribute('hidden', !attrs);
    el.style.display = attrs ? '' : 'none';
    for (const [k, v] of Object.entries(attrs ?? {})) el.setAttribute(k, v);
  };
  put(ring, sel && { cx: sel.x + 0.5, cy: sel.y + 0.5, r });
  const f = state.splitFrom;
  const end = to ?? f;
  put(from, f && { cx: f[0] + 0.5, cy: f[1] + 0.5, r: r / 2 });
  put(line, f && { x1: f[0] + 0.5, y1: f[1] + 0.5, x2: end[0] + 0.5, y2: end[1] + 0.5 });
  svg.dataset.split = f ? 'drawing' : '';
}

function editPointerDown(e) {
  const cell = cellFromEvent(e);
  if (state.editMode === 'merge' && state.selected) {
    const { x, y } = state.selected;
    setEditMode(null);
    addEdit({ op: 'merge', at: [[x, y], cell] });
  } else if (state.editMode === 'split') {
    e.preventDefault();
    if (state.splitFrom) {
      finishSplit(cell);
      return;
    }
    ui.canvas.setPointerCapture?.(e.pointerId);
    state.splitFrom = cell;
    state.splitDrag = true;
    drawOverlay();
  } else {
    select({ x: cell[0], y: cell[1] });
  }
}

function editPointerMove(e) {
  drawOverlay(cellFromEvent(e));
}

/** A drag ends the line where it is let go; a click leaves the first point for a second click. */
function editPointerUp(e) {
  state.splitDrag = false;
  const cell = cellFromEvent(e);
  if (cell[0] !== state.splitFrom[0] || cell[1] !== state.splitFrom[1]) finishSplit(cell);
}

function finishSplit(to) {
  const from = state.splitFrom;
  setEditMode(null);
  addEdit({ op: 'split', line: [from, to] });
}

/** Merge… finished from the keyboard: the selected room with Rooms row `id` (a cell inside it). */
async function mergeWithRoom(id) {
  const { x, y } = state.selected;
  setEditMode(null);
  try {
    const other = await state.chain.call('roomAt', { id });
    if (other) await addEdit({ op: 'merge', at: [[x, y], [other.x, other.y]] });
  } catch (err) {
    showError(err);
  }
}

async function importEdits(file) {
  const list = parseEdits(await file.text());
  if (list instanceof Error) {
    showError(list);
    return;
  }
  await sendEdits(list, `Imported ${list.length} edit${list.length === 1 ? '' : 's'} from ${file.name}.`);
}

function wireEdits() {
  const ed = ui.edit;
  const point = () => [state.selected.x, state.selected.y];
  ed.typeApply.addEventListener('click', () => addEdit({ op: 'type', at: point(), type: ed.type.value }));
  ed.nameForm.addEventListener('submit', (e) => {
    e.preventDefault();
    const name = ed.name.value.trim();
    if (!name) showError(new Error('Type a name for the room first.'));
    else if (state.selected?.room) addEdit({ op: 'name', at: point(), name });
  });
  ed.merge.addEventListener('click', () => setEditMode(state.editMode === 'merge' ? null : 'merge'));
  ed.split.addEventListener('click', () => setEditMode(state.editMode === 'split' ? null : 'split'));
  ed.undo.addEventListener('click', undoEdit);
  ed.clear.addEventListener('click', () => sendEdits([], 'Cleared the edits.'));
  ed.exportEdits.addEventListener('click', () => save('edits.json', `${JSON.stringify(state.edits, null, 2)}\n`, 'application/json'));
  ed.importEdits.addEventListener('change', async () => {
    const [file] = ed.importEdits.files;
    ed.importEdits.value = '';
    if (file) await importEdits(file).catch(showError);
  });
  const pick = (e) => {
    const tr = e.target.closest('tr[data-room]');
    if (!tr || !state.stats) return;
    if (e.type === 'keydown' && e.key !== 'Enter' && e.key !== ' ') return;
    e.preventDefault();
    const id = Number(tr.dataset.room);
    if (state.editMode === 'merge' && state.selected) mergeWithRoom(id);
    else select({ id });
  };
  ui.rooms.addEventListener('click', pick);
  ui.rooms.addEventListener('keydown', pick);
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
      const r = await fetchSampleFile(state.sample, 'truth.json');
      setReference(await r.text(), `${state.sample}/truth.json`);
    }),
  );
  ui.referenceClear.addEventListener('click', () =>
    attempt(async () => {
      takeStats(await state.chain.call('setReference', { json: null }));
      state.referenceJson = null;
      updateReferenceControls();
      say('Reference cleared.');
      requestRedraw();
    }),
  );

  const ex = ui.exports;
  const exporter = (name, type, method, args = () => []) => () =>
    attempt(async () => save(name, await invoke(method, ...args()), type));
  ex.world.addEventListener('click', exporter('world.json', 'application/json', 'bestWorldJson'));
  ex.labels.addEventListener('click', exporter('labels.pgm', 'image/x-portable-graymap', 'labelsPgm'));
  ex.png.addEventListener('click', exporter('overlay.png', 'image/png', 'toPng', () => [{ show: state.show, cloud: state.cloud, labels: state.labels }]));
  ex.graph.addEventListener('click', exporter('graph.json', 'application/json', 'graphJson'));
  ex.report.addEventListener('click', exporter('report.json', 'application/json', 'reportJson'));
  ex.geojson.addEventListener('click', exporter('world.geojson', 'application/geo+json', 'geojson', () => (ui.georef.value.trim() ? [ui.georef.value.trim()] : [])));
  ex.svg.addEventListener('click', exporter('world.svg', 'image/svg+xml', 'svg'));
  ex.glb.addEventListener('click', exporter('world.glb', 'model/gltf-binary', 'worldGlb', () => [heights()]));

  // The viewport's listeners first: a painting stroke asks it whether a pinch is going on.
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
  ui.route.form.addEventListener('submit', (e) => {
    e.preventDefault();
    attempt(() => state.route.submit());
  });
  wireEdits();
  ui.canvas.addEventListener('pointerdown', onPointerDown);
  ui.canvas.addEventListener('pointermove', onPointerMove);
  ui.canvas.addEventListener('pointerup', onPointerUp);
  ui.canvas.addEventListener('pointercancel', onPointerUp);
  ui.canvas.addEventListener('pointermove', onHover);
  ui.canvas.addEventListener('pointerleave', onLeave);
  const tableUse = (on) => {
    state.tableInUse = on || ui.rooms.contains(document.activeElement) || ui.rooms.matches(':hover');
    wantRoomDetails();
  };
  ui.rooms.addEventListener('focusin', (e) => {
    tableUse(true);
    pointRoom(e.target.closest('tr'), true);
  });
  ui.rooms.addEventListener('focusout', (e) => {
    if (!state.hover.pinned) setHover(0);
    tableUse(ui.rooms.contains(e.relatedTarget));
  });
  ui.rooms.addEventListener('mouseover', (e) => {
    tableUse(true);
    pointRoom(e.target.closest('tr'), false);
  });
  ui.rooms.addEventListener('mouseleave', () => {
    if (!state.hover.pinned && !ui.rooms.contains(document.activeElement)) setHover(0);
    tableUse(false);
  });
  document.addEventListener('keydown', (e) => {
    if (e.key === 'Escape' && state.hover.id) {
      setHover(0);
      wantRoomDetails();
    }
  });
  document.addEventListener('keydown', onKey);

  onDroppedFiles(ui.stage, (files) => attempt(() => openFiles(files)));
  new ResizeObserver(() => fit()).observe(ui.stage);
  window.addEventListener('resize', fit);
}

/** For tests and the curious: the page's numbers, read from the running chain. */
function expose() {
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
    /** What the page waits for (for tests that time out waiting for idle()). */
    waits() {
      const w = state.weak;
      const r = (f) => ({ inFlight: f.inFlight, again: f.again, generation: f.generation, readAt: f.readAt });
      return {
        running: state.running,
        dataRunning: document.documentElement.dataset.running,
        inFlight: state.inFlight,
        redrawPending: state.redrawPending,
        picture: Boolean(state.picture),
        busy: state.chain.busy,
        generation: state.stats?.generation,
        iteration: state.stats?.iteration,
        rooms: r(state.rooms),
        weak: w && { iteration: w.stats?.iteration, generation: w.stats?.generation, inFlight: w.inFlight, redrawPending: w.redrawPending, picture: Boolean(w.picture), busy: w.chain.busy, rooms: r(w.rooms) },
      };
    },
    /** Resolves once the page has drawn the chain's latest state and waits for nothing. */
    idle() {
      return new Promise((resolve) => {
        const check = () => {
          const paused = !state.running && document.documentElement.dataset.running === 'false';
          const w = state.weak;
          const weakIdle = !w || (w.stats && w.stats.iteration === state.stats?.iteration && !w.inFlight && !w.redrawPending && !w.picture && w.chain.busy === 0 && w.rooms.current(w.stats));
          if (paused && !state.inFlight && !state.redrawPending && !state.picture && state.chain.busy === 0 && state.rooms.current(state.stats) && weakIdle) resolve();
          else requestAnimationFrame(check);
        };
        requestAnimationFrame(check);
      });
    },
    snapshot() {
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
    },
  };
}

async function main() {
  wire();
  expose();
  if (!(await loadWasm(init))) return;
  state.chain = new RemoteChain(chainFailed, chainSettled);
  state.chain.onWings = chainWings;
  state.rooms = new RoomsFeed(() => state.chain, showRooms);
  state.route = new RouteView({ ...ui.route, canvas: ui.canvas }, {
    plan: (from, to) => invoke('route', from[0], from[1], to[0], to[1]),
    rooms: () => state.rooms.rooms,
    size: () => ({ width: state.map.width, height: state.map.height }),
    cellOf: (e) => cellFromEvent(e),
  });
  ui.version.textContent = version();
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
