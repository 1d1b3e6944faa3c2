// The live mapper's chain in a Web Worker, so that the page never blocks a frame: a step of
// the chain can take hundreds of milliseconds (a Markov logic inference with knowledge
// supervision on a large map), which here delays only the next picture, never the page.
//
// The worker owns the map and the `Mapper`; the page sends requests ({ id, op, args }) and
// gets replies ({ id, result } or { id, error }). While running, the worker iterates in slices
// of SLICE_MS and, between slices, answers requests, among them `frame`: the picture of the map
// and of the scene graph as ImageBitmaps (transferred, not copied), the statistics and the new
// trace points. Same map, seed and settings, same chain as on the main thread or natively.
//
// The chain and its pictures are the mapper module's (ksmcmc.js). The best world's rooms and
// everything made from them (the exports, routes, the report) are the plan module's
// (ksmcmc_plan.js), the rules page's inference and weight learning the rules module's
// (ksmcmc_rules.js): the worker imports each when first asked for something of it, which for
// the live mapper is once the best world has units, so that the page starts with the mapper
// module alone. They get plain text and bytes: the map's PGM and YAML and `Mapper.planInput()`,
// from which the plan module's `Plan` finds the rooms as the chain would.
//
// A building whose walls follow several directions is explained wing by wing, as
// `ksmcmc floorplan` does (floorplan::wings): once the chain has stopped, the plan module says
// how many wings there are, and the worker runs a chain per wing on that wing's map, turned by
// its direction, for as many iterations as the first chain ran, side by side in workers of
// their own (wing-workers.js), as natively on threads.
// The plan of the stopped chain is then made with the wings' chains, its units at their
// angles: byte for byte what `ksmcmc floorplan --iterations N` writes.

import init, { Map as OccMap, Mapper, renderMapperRgba, renderSceneGraphRgba, wasmHeapBytes } from '../pkg/ksmcmc.js';
import { buildMap } from './map-source.js';
import { loadModule } from './modules.js';
import { scheduler, SLICE_MS, turnDue } from './scheduler.js';
import { wingSettings } from './wing-chains.js';
import { runWingWorkers } from './wing-workers.js';

/**
 * While running, pictures take at most this share of the worker's time: a large map's picture
 * costs milliseconds, and the page would ask for one every frame. With the rooms' share
 * (mapper/rooms.js) the chain keeps at least 60 % of it.
 */
const DRAW_SHARE = 0.2;
/** The `Mapper` methods the page may call through `invoke`. */
const MAPPER_METHODS = new Set(['worldJson', 'setEdits', 'editsJson']);
/**
 * The best world's `Plan` methods the page may call through `invoke` (exports, the report, the
 * rooms, routes through them and the 3D model); `bestWorldJson` is the plan's `worldJson`, and
 * `toPng` draws what the page shows (below).
 */
const PLAN_METHODS = new Set(['bestWorldJson', 'labelsPgm', 'graphJson', 'reportJson', 'toPng', 'roomsJson', 'roomTypesJson', 'geojson', 'svg', 'route', 'worldGlb', 'placeholdersJson']);

const loadPlan = () => loadModule('ksmcmc_plan.js');
const loadRules = () => loadModule('ksmcmc_rules.js');

const ready = init();
const state = {
  map: null,
  mapper: null,
  /** Counts chains started: a reply about an older chain is told apart by it. */
  generation: 0,
  running: false,
  /** 'auto' (time slices) or a number of iterations per picture. */
  ipf: 'auto',
  /** A `frame` request waiting for the next slice: { id, view }. */
  frame: null,
  /** Pause when the chain settles, and whether it was settled when it started running. */
  stopWhenSettled: false,
  wasSettled: false,
  /** Milliseconds a picture takes (a running average), and when the last one was done. */
  drawMs: 0,
  drawnAt: 0,
  /** The map's PGM and YAML for the plan module ({ pgm, yaml }), made when the first plan is. */
  floor: null,
  /**
   * The last plan made: { key, plan, wings, world }. Its room ids carry over to the next while
   * edits are in force. `wings`: whether it was made with its wings' chains (then `world` is
   * its world's JSON text, which the best world's picture shows), or needs none.
   */
  plan: null,
  /** A plan on its way: { key, promise }, for requests that come while the wings run. */
  planning: null,
  /** The chain's settings as the page gave them (JSON text), for the wings' chains. */
  config: '',
  /** The wings being explained: { wing, of, iteration, target } (the first wing is 1). */
  wings: null,
  /** The modules loaded besides the mapper module (for the heap's size). */
  modules: new Set(),
};

// The loop yields to the event loop between slices (lib/scheduler.js).
const schedule = scheduler(loop);

/** Numbers the statistics in the order they are made. */
let seq = 0;

function stats() {
  const m = state.mapper;
  return {
    seq: ++seq,
    generation: state.generation,
    running: state.running,
    width: m.width,
    height: m.height,
    seed: String(m.seed),
    iteration: m.iteration,
    logPosterior: m.logPosterior,
    bestLogPosterior: m.bestLogPosterior,
    bestIteration: m.bestIteration,
    acceptance: m.acceptance,
    units: m.units,
    doors: m.doors,
    bestUnits: m.bestUnits,
    bestDoors: m.bestDoors,
    bestPredictionRate: m.bestPredictionRate,
    rotationDeg: m.rotationDeg,
    setupMs: m.setupMs,
    elapsedMs: m.elapsedMs,
    traceLength: m.traceLength,
    hasReference: m.hasReference,
    settledAt: m.settledAt ?? null,
    improvedAt: m.improvedAt ?? null,
    settleWindow: m.settleWindow,
    wings: state.wings ? { ...state.wings } : null,
    ...wingsDone(),
  };
}

/**
 * A new chain on `map` (the current one if not given). If it cannot start, nothing changes and
 * the error is the reply. A reference world that does not fit the new map is dropped.
 */
function start(map, { config, seed, reference }) {
  // A person's edits stay through Reset (the same map); a new map starts without them.
  const edits = !map && state.mapper ? state.mapper.editsJson() : '[]';
  const mapper = new Mapper(map ?? state.map, config, seed);
  if (edits !== '[]') {
    try {
      mapper.setEdits(edits);
    } catch (err) {
      mapper.free();
      throw err;
    }
  }
  let referenceDropped = false;
  if (reference != null) {
    try {
      mapper.setReference(reference);
    } catch {
      referenceDropped = true;
    }
  }
  if (map && state.map !== map) {
    state.map?.free();
    state.map = map;
    // Another map: its plans are made on another floor, and no room ids carry over.
    state.floor = null;
    state.plan?.plan.free();
    state.plan = null;
  }
  state.mapper?.free();
  state.mapper = mapper;
  state.config = config ?? '';
  state.generation++;
  state.running = false;
  dropFrame();
  return { stats: stats(), referenceDropped };
}

/** Answers a waiting `frame` request with nothing (its chain is gone). */
function dropFrame() {
  if (!state.frame) return;
  postMessage({ id: state.frame.id, result: null });
  state.frame = null;
}

function rgbaBitmap(rendered) {
  try {
    return createImageBitmap(new ImageData(rendered.rgba, rendered.width, rendered.height));
  } finally {
    rendered.free();
  }
}

/** Draws the map with the world and the scene graph, and collects the new trace points. */
async function frame(id, view) {
  const t0 = performance.now();
  const m = state.mapper;
  const s = stats();
  const world = view.show === 'best' ? planWorld() : undefined;
  const { show, cloud, labels, unitLabels, legend, scale } = view;
  const picture = rgbaBitmap(renderMapperRgba(m, { show, cloud, labels, unitLabels, legend, scale, world }));
  const graph = rgbaBitmap(renderSceneGraphRgba(m, view.graphWidth, view.graphHeight, view.graphShow));
  const trace = m.traceLength > view.traceFrom ? m.trace(view.traceFrom) : null;
  state.drawnAt = performance.now();
  state.drawMs = 0.8 * state.drawMs + 0.2 * (state.drawnAt - t0);
  const result = { stats: s, trace, picture: await picture, graph: await graph };
  const transfer = [result.picture, result.graph];
  if (trace) transfer.push(trace.iteration.buffer, trace.logPosterior.buffer, trace.acceptance.buffer, trace.units.buffer);
  postMessage({ id, result }, transfer);
}

function fail(err) {
  state.running = false;
  dropFrame();
  postMessage({ event: 'error', message: err instanceof Error ? err.message : String(err), stats: state.mapper ? stats() : null });
}

/** One slice of the running chain, then the waiting picture, if any. */
function loop() {
  if (!state.running || !state.mapper) return;
  // In `auto` mode a waiting picture is drawn once the chain has had its share of the time.
  let waiting = state.frame;
  if (waiting && state.ipf === 'auto' && !turnDue(state.drawnAt, state.drawMs, DRAW_SHARE)) waiting = null;
  try {
    if (state.ipf === 'auto') state.mapper.runFor(SLICE_MS);
    else if (waiting) state.mapper.step(state.ipf);
    if (waiting) {
      state.frame = null;
      frame(waiting.id, waiting.view).catch(fail);
    }
  } catch (err) {
    fail(err);
    return;
  }
  if (state.stopWhenSettled && !state.wasSettled && state.mapper.settledAt !== undefined) {
    state.running = false;
    dropFrame();
    postMessage({ event: 'settled', stats: stats() });
    return;
  }
  if (state.ipf === 'auto') schedule();
}

/** The cell of room `id` nearest the mean of its cells (inside it, away from its walls), or null. */
function innerCell(ids, width, id) {
  let n = 0;
  let sx = 0;
  let sy = 0;
  for (let i = 0; i < ids.length; i++) {
    if (ids[i] !== id) continue;
    n++;
    sx += i % width;
    sy += Math.floor(i / width);
  }
  if (n === 0) return null;
  const [mx, my] = [sx / n, sy / n];
  let best = null;
  let bestD = Infinity;
  for (let i = 0; i < ids.length; i++) {
    if (ids[i] !== id) continue;
    const d = (i % width - mx) ** 2 + (Math.floor(i / width) - my) ** 2;
    if (d < bestD) [best, bestD] = [[i % width, Math.floor(i / width)], d];
  }
  return best;
}

/**
 * The wings explained for the best world as it is now: how many (`wingsDone`, 0 for none), and
 * their world's units and K(W,M) (`wingsUnits`, `wingsPredictionRate`).
 */
function wingsDone() {
  const p = state.plan;
  if (!p?.wings || !p.count || p.key !== planKey()) return { wingsDone: 0 };
  return { wingsDone: p.count, wingsUnits: p.units, wingsPredictionRate: p.rate };
}

/** What a plan is made of: the chain, its best world and its edits. */
function planKey() {
  const m = state.mapper;
  return `${state.generation} ${m.bestIteration} ${m.bestLogPosterior} ${m.editsJson()}`;
}

/**
 * The `Plan` of the chain's best world as it is now: made again when the chain, its best world
 * or its edits have changed. While edits are in force, the rooms keep the ids of the plan shown
 * before. Once the chain has stopped, a building of several wings is explained wing by wing
 * (see the top of this file) before the plan is handed out; while it runs, the plan is the one
 * chain's.
 */
async function plan() {
  if (!state.mapper) throw new Error('no chain yet');
  const key = planKey();
  if (state.plan?.key === key && (state.plan.wings || state.running)) return state.plan.plan;
  if (state.planning?.key === key) return state.planning.promise;
  const promise = makePlan(key);
  state.planning = { key, promise };
  try {
    return await promise;
  } finally {
    if (state.planning?.promise === promise) state.planning = null;
  }
}

async function makePlan(key) {
  const x = await loadPlan();
  state.modules.add(x);
  const again = () => {
    state.planning = null;
    return plan();
  };
  if (!state.mapper || planKey() !== key) return again();
  state.floor ??= { pgm: state.map.toPgm(), yaml: state.map.toYaml('map.pgm') };
  if (state.plan?.key !== key) keep(key, newPlan(x, state.mapper.planInput()), { wings: false });
  const first = state.plan.plan;
  const config = wingSettings(state.config);
  if (first.wingCount === 0 || !config) {
    state.plan.wings = true;
    return first;
  }
  if (state.running) return first;
  const { floor } = state;
  const input = state.mapper.planInput();
  const inputs = await runWings(first, floor, config, key);
  // The chain ran on or changed meanwhile: the plan of what it is now.
  if (!inputs) return again();
  const made = new x.Plan(floor.pgm, floor.yaml, input, undefined, inputs);
  const report = JSON.parse(made.reportJson());
  keep(key, made, { wings: true, count: inputs.length, units: report.units, rate: report.cell_prediction_rate });
  postMessage({ event: 'wings', stats: stats() });
  return made;
}

/** A plan of the chain's `input` (room ids carried over from the last plan while edits are in force). */
function newPlan(x, input) {
  const edits = state.mapper.editsJson();
  const previous = edits !== '[]' && state.plan ? state.plan.plan.roomLabels() : undefined;
  return new x.Plan(state.floor.pgm, state.floor.yaml, input, previous);
}

/**
 * The `world.json` of the plan of the chain's best world as it is now, if that plan is made:
 * the best world with its rooms (and, for a building of wings, its units at their angles),
 * which the page draws and labels room by room (issue 33). Read once per plan.
 */
function planWorld() {
  const p = state.plan;
  if (!p || p.key !== planKey()) return undefined;
  p.world ??= p.plan.worldJson();
  return p.world;
}

/** Makes `plan` the last plan made, for `key`. */
function keep(key, plan, { wings, count = 0, units = 0, rate = 0 }) {
  if (state.plan?.plan !== plan) state.plan?.plan.free();
  // Its world.json text is read when first drawn (planWorld).
  state.plan = { key, plan, wings, count, world: null, units, rate };
}

/**
 * Runs the chains of the wings of plan `first` (its `wingCount`), each for as many iterations as
 * the first chain ran, with its seed, side by side in workers. Returns their plan inputs in
 * order, or null if the chain ran on, changed or was replaced meanwhile.
 */
async function runWings(first, floor, config, key) {
  const m = state.mapper;
  const [generation, target] = [state.generation, m.iteration];
  const gone = () => state.running || state.generation !== generation || !state.mapper || planKey() !== key;
  const onProgress = (p) => {
    state.wings = { ...p, target };
    if (p.iteration === 0) postMessage({ event: 'wings', stats: stats() });
  };
  try {
    return await runWingWorkers({ first, yaml: floor.yaml, config, seed: m.seed, target, gone, onProgress });
  } finally {
    state.wings = null;
  }
}

/**
 * The PNG of the picture the page shows (`options`: show, cloud, labels, scale), drawn by the
 * mapper module and encoded by the plan module; the best world is the plan's (the world with
 * its rooms), which makes it the `overlay.png` of `ksmcmc floorplan`.
 */
async function toPng({ show = 'current', cloud = false, labels = true, unitLabels = false, scale = 1 } = {}) {
  const x = await loadPlan();
  const world = show === 'best' ? (await plan()).worldJson() : undefined;
  const r = renderMapperRgba(state.mapper, { show, cloud, labels, unitLabels, scale, world });
  try {
    return x.encodePng(r.width, r.height, r.rgba);
  } finally {
    r.free();
  }
}

/**
 * Rooms, room types and labels of a best world without units: none yet (its plan would be the
 * free space as rooms of no unit), without loading the plan module before the chain has found
 * something.
 */
function noRooms(details) {
  const m = state.mapper;
  return { text: '[]', types: details ? '[]' : null, labels: details ? new Uint16Array(m.width * m.height) : null };
}

const ops = {
  /**
   * A new map from `source`, and a chain on it. With `withCells`, the reply carries the map's
   * cells, from which the page makes its own copy of the map: the bytes are decoded here only,
   * not a second time on the page's thread (a task of 130 - 150 ms for Cartesium's PNG).
   */
  load({ source, withCells = false, ...args }) {
    const map = buildMap(source, OccMap);
    const cells = withCells ? { width: map.width, height: map.height, codes: map.cells() } : undefined;
    try {
      return { ...start(map, args), cells };
    } catch (err) {
      map.free();
      throw err;
    }
  },
  start(args) {
    if (!state.map) throw new Error('no map yet');
    return start(null, args);
  },
  /**
   * The map changed (a paint stroke): the chain takes the new map, of the same size, and goes
   * on from its world (`Mapper.updateMap`) instead of starting over. Replies with how many
   * cells changed and the chain's numbers; if the map is refused, nothing changes.
   */
  updateMap({ source }) {
    const map = buildMap(source, OccMap);
    let changed;
    try {
      changed = state.mapper.updateMap(map);
    } catch (err) {
      map.free();
      throw err;
    }
    if (changed > 0) {
      state.map?.free();
      state.map = map;
      // A changed map is a new climb: "stop when settled" waits for it to settle again.
      state.wasSettled = false;
      // The plan is made again, on the new map, from the chain's best world as it is now (its
      // key may not have changed); while edits are in force its rooms keep the shown ids.
      state.floor = null;
      if (state.plan) state.plan.key = null;
    } else {
      map.free();
    }
    return { stats: stats(), changed };
  },
  play({ ipf, stopWhenSettled }) {
    state.ipf = ipf;
    state.stopWhenSettled = Boolean(stopWhenSettled);
    state.wasSettled = state.mapper.settledAt !== undefined;
    state.running = true;
    schedule();
    return stats();
  },
  stopWhenSettled({ on }) {
    state.stopWhenSettled = Boolean(on);
    state.wasSettled = state.mapper.settledAt !== undefined;
    return stats();
  },
  pause() {
    state.running = false;
    // A picture waiting for the next slice would wait for ever: it is drawn now (its reply
    // follows this one's).
    const waiting = state.frame;
    state.frame = null;
    if (waiting) frame(waiting.id, waiting.view).catch(fail);
    return stats();
  },
  step({ n }) {
    state.mapper.step(n);
    return stats();
  },
  setReference({ json }) {
    state.mapper.setReference(json ?? undefined);
    return stats();
  },
  /** What the rules `kb` infer from the best world (the rules page): `inferWorld`'s JSON. */
  async infer({ kb, resolution }) {
    const generation = state.generation;
    // The typed best world: its rooms are no evidence.
    const world = JSON.stringify(JSON.parse(state.mapper.planInput()).world);
    const x = await loadRules();
    state.modules.add(x);
    try {
      return { generation, world, inferred: x.inferWorld(kb, world, resolution), error: null };
    } catch (err) {
      return { generation, world, inferred: null, error: err instanceof Error ? err.message : String(err) };
    }
  },
  /**
   * The rules `kb` with weights learned from a labelled world (the rules page): `learnRules`'s
   * text. Needs no chain.
   */
  async learn({ kb, world, resolution, method }) {
    const x = await loadRules();
    state.modules.add(x);
    return x.learnRules(kb, world, resolution, method);
  },
  /**
   * The best world's rooms (`roomsJson` text), and with `details` their type marginals
   * (`roomTypesJson` text) and the room id of every cell (`roomLabels`, transferred), unless
   * the page has them: rooms whose text is `known`, details read with rooms `knownDetails`
   * (then `{ same: true }`, or the text alone).
   */
  async rooms({ details, known, knownDetails }) {
    if (state.mapper.bestUnits === 0) {
      const none = noRooms(details);
      return none.text === known && (!details || none.text === knownDetails) ? { same: true } : none;
    }
    const p = await plan();
    const text = p.roomsJson();
    const withDetails = Boolean(details) && text !== knownDetails;
    if (text === known && !withDetails) return { same: true };
    return { text, types: withDetails ? p.roomTypesJson() : null, labels: withDetails ? p.roomLabels() : null };
  },
  /** Bytes of the worker's wasm heaps, the mapper module's and the others' it loaded (the soak test watches them). Needs no chain. */
  heap() {
    return [...state.modules].reduce((sum, m) => sum + m.wasmHeapBytes(), wasmHeapBytes());
  },
  /**
   * The best world's room at map cell (x, y) (its id in `labelsPgm`, 0 for none) and, with
   * `id`, a cell of that room: for the page's room selection.
   */
  async roomAt({ x, y, id }) {
    const m = state.mapper;
    const ids = m.bestUnits === 0 ? new Uint16Array(m.width * m.height) : (await plan()).roomLabels();
    const { width, height } = state.mapper;
    if (id !== undefined) {
      const c = innerCell(ids, width, id);
      return c && { x: c[0], y: c[1], room: id };
    }
    if (!(x >= 0 && y >= 0 && x < width && y < height)) return null;
    return { x, y, room: ids[y * width + x] };
  },
  async invoke({ name, args = [] }) {
    if (MAPPER_METHODS.has(name)) return state.mapper[name](...args);
    if (!PLAN_METHODS.has(name)) throw new Error(`${name} is not a method the page may call`);
    if (name === 'toPng') return toPng(...args);
    const p = await plan();
    return name === 'bestWorldJson' ? p.worldJson() : p[name](...args);
  },
};

onmessage = async (e) => {
  const { id, op, args } = e.data;
  try {
    await ready;
    if (op === 'frame') {
      if (!state.mapper || (args.generation !== undefined && args.generation !== state.generation)) {
        postMessage({ id, result: null });
        return;
      }
      // While running, the picture waits for the end of the current slice (and, with a fixed
      // number of iterations per frame, for that many more iterations).
      if (state.running) {
        dropFrame();
        state.frame = { id, view: args };
        schedule();
      } else {
        await frame(id, args);
      }
      return;
    }
    if (op !== 'load' && op !== 'learn' && op !== 'heap' && !state.mapper) throw new Error('no chain yet');
    const result = await ops[op](args ?? {});
    const transfer = result instanceof Uint8Array ? [result.buffer] : result?.labels instanceof Uint16Array ? [result.labels.buffer] : [];
    postMessage({ id, result }, transfer);
  } catch (err) {
    postMessage({ id, error: err instanceof Error ? err.message : String(err) });
  }
};
