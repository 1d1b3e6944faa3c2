// The Exploration page's robot and chain in a Web Worker, so that the page never blocks a
// frame: a scan, a frontier search, a map update (`Mapper.updateMap` redoes the detectors
// where the map changed) or a step of the chain can each take milliseconds to hundreds of
// milliseconds, which here delay only the next picture.
//
// The worker owns the true map, the simulated robot (`Explorer`) and the chain (`Mapper`),
// and follows `ksmcmc explore`: the robot drives and scans; once it has driven `updateEveryM`
// metres the chain starts on its map (`new Mapper(snapshot)`), and every `updateEveryM`
// metres after that it takes the robot's map and goes on from its world
// (`mapper.updateMap(snapshot)`); when no frontier is left it takes the last map and runs on
// until it settles. The robot drives `speed` cells for each picture the page asks for (the
// speed is in cells per frame shown), and between pictures the chain iterates in slices of
// SLICE_MS, as in chain-worker.js (the run loop both share: lib/scheduler.js). Requests and
// replies are those of chain-worker.js ({ id, op, args } → { id, result } or { id, error };
// events `error` and `settled`), so the page talks to it through lib/remote-chain.js.
//
// The robot, the chain and the pictures are the exploration module's (ksmcmc_explore.js: the
// mapper module's API with the robot, so that the robot's snapshots are that module's maps the
// chain takes as they are), which is all the page loads to run. The best world with its rooms
// (`bestWorldJson`) is the plan module's `Plan` (ksmcmc_plan.js), imported when first asked
// for and made again after the chain's map or best world changed.

import init, {
  Map as OccMap,
  chainConfigDefaults,
  chainConfigOnline,
  Explorer,
  Mapper,
  renderMapperRgba,
  renderRgba,
  wasmHeapBytes,
} from '../pkg/ksmcmc_explore.js';
import { buildMap } from './map-source.js';
import { loadModule } from './modules.js';
import { scheduler, SLICE_MS, turnDue } from './scheduler.js';

/**
 * While the chain runs, pictures (with the robot's driving) take at most this share of the
 * worker's time. More than the live mapper's 0.3: here the robot's motion is the show, and the
 * robot drives only when a picture is made (a 1237 x 672 map's picture takes about 15 ms).
 */
const DRAW_SHARE = 0.5;
/** The most cells the robot drives for one picture. */
const MAX_SPEED = 64;
/**
 * The robot drives in chunks of at most this many cells, aligned on its steps from the start,
 * and an update is due at the end of a chunk: as `ksmcmc explore` drives it
 * (`floorplan::online`), so that the chain gets the same maps at the same places, whatever
 * the speed.
 */
const CHUNK = 16;
/** The most cells a `Mapper` takes (its MAX_MAPPER_CELLS): larger maps are refused when loaded. */
const MAX_CELLS = 2 ** 23;
/** The colours of cell codes 0 free, 1 unknown, 2 occupied: the library's (`render::cell_rgb`). */
const CODE_RGB = [
  [255, 255, 255],
  [160, 160, 160],
  [0, 0, 0],
];

/**
 * The end of an exploration, as `ksmcmc explore` ends it (`OnlineConfig::renew`): once the robot
 * is done, the warm chain under the whole-map sensor table and a fresh chain with that table on
 * the last map each run this many iterations (the cold budget: 5 x 20,000), and the one with
 * the higher best log posterior is kept.
 */
const RENEW_ITERATIONS = 100_000;

/** The online settings with the whole-map sensor table: the fresh chain's at the end. */
function wholeMapConfig() {
  const config = JSON.parse(chainConfigOnline());
  config.posterior.sensor = JSON.parse(chainConfigDefaults()).posterior.sensor;
  return JSON.stringify(config);
}

/** The plan module, imported and initialised when first needed (then kept). */
const loadPlan = () => loadModule('ksmcmc_plan.js');

const ready = init();
const state = {
  truth: null,
  /** Free cells of the true map: what "cells seen" is a share of; its metres per cell. */
  truthFree: 0,
  resolution: 0.05,
  explorer: null,
  mapper: null,
  /** How the robot and the chain were started: { seed, rangeM } (the chain: default settings, as `ksmcmc explore`). */
  args: null,
  /** Counts explorations started: a reply about an older one is told apart by it. */
  generation: 0,
  running: false,
  /** A `frame` request waiting for the end of the current slice: { id, view }. */
  frame: null,
  /**
   * Updates of the chain's map after its start, metres driven at the last one, where the next
   * one is due (null: `updateEveryM` from the start), and the last one's changed cells.
   */
  updates: 0,
  updatedAtM: 0,
  nextUpdateM: null,
  /** Cells the robot has driven (its steps), for chunks aligned as `ksmcmc explore` makes them. */
  steps: 0,
  /** One record per hand-over: { update (0: the chain's start), travelledM, seenFree, changed, ms }. */
  timeline: [],
  lastChanged: null,
  lastUpdateMs: null,
  /** Whether the chain has the robot's final map (the robot is done); then it runs until settled. */
  finished: false,
  /**
   * The end of the exploration: { fresh (a Mapper, while both run), warmFrom (the warm chain's
   * iteration at the switch), range (the warm chain's figures before it), done, adopted, warm,
   * fresh figures }; null before the robot is done.
   */
  renewal: null,
  settled: false,
  /** Whether the chain was settled when it last started running (Start after settling runs on). */
  wasSettled: false,
  /** The codes of the map the chain has, and of the robot's map (read at `cellsAt` scans). */
  chainCells: null,
  robotCells: null,
  cellsAt: -1,
  /** Milliseconds a picture takes (a running average), and when the last one was done. */
  drawMs: 0,
  drawnAt: 0,
  /** The last `Plan` made of the chain's best world: { key, plan }; dropped when the chain's map changes. */
  plan: null,
  /** The plan module once loaded (for the heap's size). */
  planModule: null,
};

// The loop yields to the event loop between slices (lib/scheduler.js).
const schedule = scheduler(loop);

/** Numbers the statistics in the order they are made. */
let seq = 0;

function stats() {
  const e = state.explorer;
  const m = state.mapper;
  const [x, y] = e.robot;
  return {
    seq: ++seq,
    generation: state.generation,
    running: state.running,
    width: state.truth.width,
    height: state.truth.height,
    truthFree: state.truthFree,
    resolution: state.resolution,
    seed: String(state.args.seed),
    robot: [x, y],
    travelledM: e.travelledM,
    scans: e.scans,
    seenFree: e.seenFree,
    done: e.done,
    updates: state.updates,
    updatedAtM: state.updatedAtM,
    lastChanged: state.lastChanged,
    lastUpdateMs: state.lastUpdateMs,
    finished: state.finished,
    settled: state.settled,
    renewal: renewalStats(),
    chain: m
      ? {
          iteration: m.iteration,
          bestLogPosterior: m.bestLogPosterior,
          bestUnits: m.bestUnits,
          bestDoors: m.bestDoors,
          bestPredictionRate: m.bestPredictionRate,
          rotationDeg: m.rotationDeg,
          setupMs: m.setupMs,
          settledAt: m.settledAt ?? null,
          settleWindow: m.settleWindow,
        }
      : null,
  };
}

/** A chain's figures for the renewal's report. */
function figures(m) {
  return { logPosterior: m.bestLogPosterior, predictionRate: m.bestPredictionRate, units: m.bestUnits, iteration: m.iteration };
}

/** The renewal as the page shows it: its figures, and how far each chain has run. */
function renewalStats() {
  const r = state.renewal;
  if (!r) return null;
  const ran = r.done ? RENEW_ITERATIONS : Math.min(state.mapper.iteration - r.warmFrom, r.fresh.iteration);
  return { iterations: RENEW_ITERATIONS, ran, done: r.done, adopted: r.adopted, range: r.range, warm: r.warm, fresh: r.freshFigures };
}

/**
 * Starts the end of the exploration on the last map `snapshot`: the warm chain takes the
 * whole-map table, and a fresh chain with it starts beside it.
 */
function startRenewal(snapshot) {
  const m = state.mapper;
  const range = figures(m);
  m.useWholeMapSensor();
  const fresh = new Mapper(snapshot, wholeMapConfig(), state.args.seed);
  state.renewal = { fresh, warmFrom: m.iteration, range, done: false, adopted: false, warm: null, freshFigures: null };
}

/**
 * One slice of the renewal: each chain runs half of it until both have run RENEW_ITERATIONS;
 * then the one with the higher best log posterior is kept (the fresh one replaces the warm
 * one only if strictly higher, as natively). Returns whether the renewal is over.
 */
function renewalSlice() {
  const r = state.renewal;
  const warm = state.mapper;
  const left = (m, from) => RENEW_ITERATIONS - (m.iteration - from);
  // Timed slices, not counted ones: a chain may run a little past the budget, and the figures
  // are read once both are through it.
  for (const [m, from] of [[warm, r.warmFrom], [r.fresh, 0]]) {
    if (left(m, from) > 0) m.runFor(SLICE_MS / 2);
  }
  if (left(warm, r.warmFrom) > 0 || left(r.fresh, 0) > 0) return false;
  r.warm = figures(warm);
  r.freshFigures = figures(r.fresh);
  r.adopted = r.fresh.bestLogPosterior > warm.bestLogPosterior;
  if (r.adopted) {
    state.mapper = r.fresh;
    warm.free();
    dropPlan();
  } else {
    r.fresh.free();
  }
  r.fresh = null;
  r.done = true;
  return true;
}

/** A new robot on the true map, and no chain until it has driven the first interval. */
function start({ seed, rangeM }) {
  const explorer = new Explorer(state.truth, JSON.stringify({ range_m: rangeM }), seed);
  state.explorer?.free();
  state.mapper?.free();
  state.explorer = explorer;
  state.mapper = null;
  state.renewal?.fresh?.free();
  state.renewal = null;
  state.args = { seed, rangeM };
  state.generation++;
  state.running = false;
  state.updates = 0;
  state.updatedAtM = 0;
  state.nextUpdateM = null;
  state.steps = 0;
  state.timeline = [];
  state.lastChanged = null;
  state.lastUpdateMs = null;
  state.finished = false;
  state.settled = false;
  state.chainCells = null;
  state.robotCells = null;
  state.cellsAt = -1;
  dropPlan();
  dropFrame();
  return stats();
}

/** Forgets the plan made of the chain's best world (the chain is gone or has another map). */
function dropPlan() {
  state.plan?.plan.free();
  state.plan = null;
}

/**
 * The `Plan` of the chain's best world on the chain's map, made again when the exploration or
 * the best world has changed (an update that changed the map drops it: `update`); null if
 * there is no chain (by the time the plan module has loaded).
 */
async function plan() {
  const x = await loadPlan();
  state.planModule = x;
  const m = state.mapper;
  if (!m) return null;
  const key = `${state.generation} ${m.bestIteration} ${m.bestLogPosterior}`;
  if (state.plan?.key === key) return state.plan.plan;
  const map = m.map;
  let made;
  try {
    made = new x.Plan(map.toPgm(), map.toYaml('map.pgm'), m.planInput());
  } finally {
    map.free();
  }
  dropPlan();
  state.plan = { key, plan: made };
  return made;
}

/** Answers a waiting `frame` request with nothing (its exploration is gone). */
function dropFrame() {
  if (!state.frame) return;
  postMessage({ id: state.frame.id, result: null });
  state.frame = null;
}

/** The robot's map as cell codes, read again only when it has scanned since. */
function robotCells() {
  const e = state.explorer;
  const scans = e.scans;
  if (scans !== state.cellsAt) {
    const snapshot = e.snapshot();
    try {
      state.robotCells = snapshot.cells();
    } finally {
      snapshot.free();
    }
    state.cellsAt = scans;
  }
  return state.robotCells;
}

/**
 * Hands the robot's map to the chain: the first time a new chain on it, then `updateMap`.
 * Once the robot is done, this map is its last.
 */
function update() {
  const e = state.explorer;
  const snapshot = e.snapshot();
  const t0 = performance.now();
  try {
    if (!state.mapper) {
      // The online settings, as `ksmcmc explore` uses: a wall's ring lies behind the face the
      // robot saw (the range-sensor table).
      state.mapper = new Mapper(snapshot, chainConfigOnline(), state.args.seed);
    } else {
      state.lastChanged = state.mapper.updateMap(snapshot);
      state.updates++;
      // The chain's map changed: its plan is made again from its new best world.
      if (state.lastChanged > 0) dropPlan();
    }
    state.chainCells = snapshot.cells();
  } finally {
    snapshot.free();
  }
  state.lastUpdateMs = performance.now() - t0;
  state.updatedAtM = e.travelledM;
  state.timeline.push({
    update: state.updates,
    travelledM: state.updatedAtM,
    seenFree: e.seenFree,
    changed: state.lastChanged,
    ms: state.lastUpdateMs,
  });
  if (e.done) {
    state.finished = true;
    state.settled = false;
    state.wasSettled = false;
    const last = e.snapshot();
    try {
      startRenewal(last);
    } finally {
      last.free();
    }
  }
}

/**
 * The robot drives `cells` cells; the chain takes its map whenever it is due (every
 * `updateEveryM` metres from the start, checked at the end of each chunk) and when the robot
 * is done, as `ksmcmc explore` hands it over.
 */
function drive(cells, updateEveryM) {
  const e = state.explorer;
  let left = cells;
  while (!state.finished) {
    state.nextUpdateM ??= updateEveryM;
    if (e.done || e.travelledM >= state.nextUpdateM) {
      update();
      state.nextUpdateM += updateEveryM;
      continue;
    }
    if (left === 0) break;
    const n = Math.min(left, CHUNK - (state.steps % CHUNK));
    e.advance(n);
    state.steps += n;
    left -= n;
  }
}

/**
 * The picture: the chain's map with its best world (as the live mapper draws it), and where
 * the robot has seen more since the chain's last map, the robot's cells. Before the chain
 * starts, the robot's map alone.
 */
function picture(view) {
  const scale = view.scale;
  const cells = robotCells();
  if (!state.mapper) {
    const snapshot = state.explorer.snapshot();
    try {
      return rgbaOf(renderRgba(snapshot, undefined, scale, false));
    } finally {
      snapshot.free();
    }
  }
  const drawn = rgbaOf(renderMapperRgba(state.mapper, { show: view.plan ? 'best' : 'none', labels: view.labels, unitLabels: view.labels, scale }));
  overdraw(drawn, cells, state.chainCells, state.truth.width, scale);
  return drawn;
}

/** The pixels of a `Rendered` (copied out of wasm, which is then freed). */
function rgbaOf(rendered) {
  try {
    return { rgba: rendered.rgba, width: rendered.width, height: rendered.height };
  } finally {
    rendered.free();
  }
}

/** Paints the cells where `cells` differs from `under` (both codes, `width` per row) at `scale`. */
function overdraw({ rgba, width: pw }, cells, under, width, scale) {
  for (let i = 0; i < cells.length; i++) {
    const c = cells[i];
    if (c === under[i]) continue;
    const [r, g, b] = CODE_RGB[c];
    const x0 = (i % width) * scale;
    const y0 = Math.floor(i / width) * scale;
    for (let dy = 0; dy < scale; dy++) {
      let p = ((y0 + dy) * pw + x0) * 4;
      for (let dx = 0; dx < scale; dx++, p += 4) {
        rgba[p] = r;
        rgba[p + 1] = g;
        rgba[p + 2] = b;
        rgba[p + 3] = 255;
      }
    }
  }
}

/**
 * Drives the robot (if running), draws, and replies with the numbers, the picture (an
 * ImageBitmap, transferred) and the scan cells from `view.scanFrom` on (flat x, y pairs). If
 * the robot or the chain fails on the way (say, the chain cannot start on the robot's first
 * map), the reply is the error and the exploration stops.
 */
async function frame(id, view) {
  let result;
  try {
    if (state.running) drive(Math.min(MAX_SPEED, Math.max(1, Math.floor(view.speed))), view.updateEveryM);
    const t0 = performance.now();
    const p = picture(view);
    const s = stats();
    const scans = state.explorer.scanCells(view.scanFrom);
    state.drawnAt = performance.now();
    state.drawMs = 0.8 * state.drawMs + 0.2 * (state.drawnAt - t0);
    result = { stats: s, picture: await createImageBitmap(new ImageData(p.rgba, p.width, p.height)), scans };
  } catch (err) {
    state.running = false;
    postMessage({ id, error: err instanceof Error ? err.message : String(err) });
    return;
  }
  postMessage({ id, result }, [result.picture, result.scans.buffer]);
}

function fail(err) {
  state.running = false;
  dropFrame();
  postMessage({ event: 'error', message: err instanceof Error ? err.message : String(err), stats: state.explorer ? stats() : null });
}

/** One slice of the chain, then the waiting picture, if any; stops once the chain has settled on the last map. */
function loop() {
  if (!state.running) return;
  let waiting = state.frame;
  if (waiting && state.mapper && !turnDue(state.drawnAt, state.drawMs, DRAW_SHARE)) waiting = null;
  try {
    if (state.renewal && !state.renewal.done) renewalSlice();
    else if (state.mapper) state.mapper.runFor(SLICE_MS);
    if (waiting) {
      state.frame = null;
      frame(waiting.id, waiting.view);
    }
  } catch (err) {
    fail(err);
    return;
  }
  if (state.finished && state.renewal?.done && !state.wasSettled && state.mapper?.settledAt !== undefined) {
    state.running = false;
    state.settled = true;
    dropFrame();
    postMessage({ event: 'settled', stats: stats() });
    return;
  }
  if (state.mapper || state.frame) schedule();
}

/** Metres per cell of a map (its map.yaml's `resolution`). */
function resolutionOf(map) {
  const r = Number(/^resolution:\s*(\S+)/m.exec(map.toYaml('map.pgm'))?.[1]);
  return Number.isFinite(r) && r > 0 ? r : 0.05;
}

const ops = {
  /** A new true map (`source`, as lib/map-source.js reads it) and a robot on it. */
  load({ source, ...args }) {
    const truth = buildMap(source, OccMap);
    if (truth.width * truth.height > MAX_CELLS) {
      const size = `${truth.width}x${truth.height}`;
      truth.free();
      throw new Error(`the map is ${size} cells; the chain takes at most ${MAX_CELLS} (e.g. 4096x2048): crop or downsample it`);
    }
    const old = { truth: state.truth, truthFree: state.truthFree, resolution: state.resolution };
    try {
      state.truth = truth;
      state.truthFree = truth.counts().free;
      state.resolution = resolutionOf(truth);
      const stats = start(args);
      old.truth?.free();
      return stats;
    } catch (err) {
      Object.assign(state, old);
      truth.free();
      throw err;
    }
  },
  /** The robot back at its start (with the seed and range given) and no chain. */
  reset(args) {
    return start(args);
  },
  play() {
    state.running = true;
    state.wasSettled = state.mapper?.settledAt !== undefined && state.finished;
    schedule();
    return stats();
  },
  pause() {
    state.running = false;
    // A picture waiting for the next slice would wait for ever: it is drawn now.
    const waiting = state.frame;
    state.frame = null;
    if (waiting) frame(waiting.id, waiting.view);
    return stats();
  },
  /** Every hand-over of the robot's map to the chain so far (`state.timeline`). */
  timeline() {
    return state.timeline;
  },
  /** Bytes of the worker's wasm heaps: the mapper module's, and the plan module's once loaded. */
  heap() {
    return wasmHeapBytes() + (state.planModule?.wasmHeapBytes() ?? 0);
  },
  /**
   * The chain's best world with its rooms as world.json text (the plan module's `worldJson`,
   * what `ksmcmc explore` writes), or null before the chain starts.
   */
  async bestWorldJson() {
    return state.mapper ? ((await plan())?.worldJson() ?? null) : null;
  },
};

onmessage = async (e) => {
  const { id, op, args } = e.data;
  try {
    await ready;
    if (op === 'frame') {
      if (!state.explorer || (args.generation !== undefined && args.generation !== state.generation)) {
        postMessage({ id, result: null });
        return;
      }
      // While the chain runs, the picture waits for the end of the current slice.
      if (state.running && state.mapper) {
        dropFrame();
        state.frame = { id, view: args };
        schedule();
      } else {
        await frame(id, args);
      }
      return;
    }
    if (!(op in ops)) throw new Error(`unknown request ${op}`);
    if (op !== 'load' && op !== 'heap' && !state.explorer) throw new Error('no map yet');
    postMessage({ id, result: await ops[op](args ?? {}) });
  } catch (err) {
    postMessage({ id, error: err instanceof Error ? err.message : String(err) });
  }
};
