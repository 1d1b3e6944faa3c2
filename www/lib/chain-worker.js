// The live mapper's chain in a Web Worker, so that the page never blocks a frame: a step of
// the chain can take hundreds of milliseconds (a Markov logic inference with knowledge
// supervision on a large map), which here delays only the next picture, never the page.
//
// The worker owns the map and the `Mapper`; the page sends requests ({ id, op, args }) and
// gets replies ({ id, result } or { id, error }). While running, the worker iterates in slices
// of SLICE_MS and, between slices, answers requests, among them `frame`: the picture of the map
// and of the scene graph as ImageBitmaps (transferred, not copied), the statistics and the new
// trace points. Same map, seed and settings, same chain as on the main thread or natively.

import init, { Mapper, inferWorld, learnRules, renderMapperRgba, renderSceneGraphRgba, wasmHeapBytes } from '../pkg/ksmcmc.js';
import { buildMap } from './map-source.js';

/** Milliseconds of iterations between looking at the page's requests. */
const SLICE_MS = 8;
/**
 * While running, pictures take at most this share of the worker's time: a large map's picture
 * costs milliseconds, and the page would ask for one every frame.
 */
const DRAW_SHARE = 0.3;
/**
 * The mapper's methods the page may call through `invoke` (exports, the report, the best
 * world's rooms, routes through them and its 3D model).
 */
const INVOKABLE = new Set(['bestWorldJson', 'worldJson', 'labelsPgm', 'graphJson', 'reportJson', 'toPng', 'roomsJson', 'roomTypesJson', 'geojson', 'svg', 'route', 'worldGlb', 'setEdits', 'editsJson']);

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
  scheduled: false,
  /** Pause when the chain settles, and whether it was settled when it started running. */
  stopWhenSettled: false,
  wasSettled: false,
  /** Milliseconds a picture takes (a running average), and when the last one was done. */
  drawMs: 0,
  drawnAt: 0,
};

// The loop yields to the event loop between slices through a MessageChannel (setTimeout would
// be clamped to 4 ms).
const tick = new MessageChannel();
tick.port1.onmessage = loop;
function schedule() {
  if (state.scheduled) return;
  state.scheduled = true;
  tick.port2.postMessage(0);
}

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
  }
  state.mapper?.free();
  state.mapper = mapper;
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
  const picture = rgbaBitmap(renderMapperRgba(m, { show: view.show, cloud: view.cloud, labels: view.labels, scale: view.scale }));
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
  state.scheduled = false;
  if (!state.running || !state.mapper) return;
  // In `auto` mode a waiting picture is drawn once the chain has had its share of the time.
  let waiting = state.frame;
  if (waiting && state.ipf === 'auto' && performance.now() - state.drawnAt < (state.drawMs * (1 - DRAW_SHARE)) / DRAW_SHARE) {
    waiting = null;
  }
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

/** The room ids of a 16-bit binary PGM (`labelsPgm`: "P5\\nW H\\n65535\\n", big-endian samples). */
function labels(pgm) {
  const head = new TextDecoder().decode(pgm.subarray(0, 64)).match(/^P5\s+(\d+)\s+(\d+)\s+(\d+)\s/);
  if (!head) throw new Error('the labels are not a binary PGM');
  const [whole, w, h] = head;
  const width = Number(w);
  const height = Number(h);
  const data = new DataView(pgm.buffer, pgm.byteOffset + whole.length);
  const ids = new Uint16Array(width * height);
  for (let i = 0; i < ids.length; i++) ids[i] = data.getUint16(2 * i);
  return { width, height, ids };
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

const ops = {
  load({ source, ...args }) {
    const map = buildMap(source);
    try {
      return start(map, args);
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
    const map = buildMap(source);
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
  infer({ kb, resolution }) {
    const world = state.mapper.bestWorldJson();
    try {
      return { generation: state.generation, world, inferred: inferWorld(kb, world, resolution), error: null };
    } catch (err) {
      return { generation: state.generation, world, inferred: null, error: err instanceof Error ? err.message : String(err) };
    }
  },
  /**
   * The rules `kb` with weights learned from a labelled world (the rules page): `learnRules`'s
   * text. Needs no chain.
   */
  learn({ kb, world, resolution, method }) {
    return learnRules(kb, world, resolution, method);
  },
  /**
   * The best world's rooms (`roomsJson` text), and with `details` their type marginals
   * (`roomTypesJson` text) and the room id of every cell (`roomLabels`, transferred), unless
   * the page has them: rooms whose text is `known`, details read with rooms `knownDetails`
   * (then `{ same: true }`, or the text alone).
   */
  rooms({ details, known, knownDetails }) {
    const m = state.mapper;
    const text = m.roomsJson();
    const withDetails = Boolean(details) && text !== knownDetails;
    if (text === known && !withDetails) return { same: true };
    return { text, types: withDetails ? m.roomTypesJson() : null, labels: withDetails ? m.roomLabels() : null };
  },
  /** Bytes of the worker's wasm heap (the soak test watches it). Needs no chain. */
  heap() {
    return wasmHeapBytes();
  },
  /**
   * The best world's room at map cell (x, y) (its id in `labelsPgm`, 0 for none) and, with
   * `id`, a cell of that room: for the page's room selection.
   */
  roomAt({ x, y, id }) {
    const { width, height, ids } = labels(state.mapper.labelsPgm());
    if (id !== undefined) {
      const c = innerCell(ids, width, id);
      return c && { x: c[0], y: c[1], room: id };
    }
    if (!(x >= 0 && y >= 0 && x < width && y < height)) return null;
    return { x, y, room: ids[y * width + x] };
  },
  invoke({ name, args = [] }) {
    if (!INVOKABLE.has(name)) throw new Error(`${name} is not a method the page may call`);
    return state.mapper[name](...args);
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
    const result = ops[op](args ?? {});
    const transfer = result instanceof Uint8Array ? [result.buffer] : result?.labels instanceof Uint16Array ? [result.labels.buffer] : [];
    postMessage({ id, result }, transfer);
  } catch (err) {
    postMessage({ id, error: err instanceof Error ? err.message : String(err) });
  }
};
