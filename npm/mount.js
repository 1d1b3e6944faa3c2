// A small live-mapper widget for documentation pages:
//
//   import { mount } from 'ksmcmc/mount.js';
//   const widget = await mount(document.getElementById('demo'), { sample: 'office-small', seed: 1, autoplay: true });
//
// builds, inside the element, the map with the chain's current world drawn over it, the scene
// graph beside it, Start/Pause, Step and Reset buttons, cloud and best-world switches, zoom
// buttons and a line of statistics, and runs the chain in requestAnimationFrame with a time
// budget per frame so the page stays responsive. The map zooms and pans by wheel, pinch, drag
// and keys (+ − 0 and the arrows with the map focused; viewport.js, shared with the demo).
// Plain DOM, no framework, no network: samples are remade by the synthetic generator (see
// samples.js; its module, ksmcmc_synth.js, is loaded only for a sample), and the styles are
// injected once, scoped to the widget's class.

import init, { Map as OccupancyMap, Mapper, drawMapper, drawSceneGraph } from './ksmcmc.js';
import { SAMPLES, sampleRecipe } from './samples.js';
import { Viewport, detailScale } from './viewport.js';
import { runWingChains, wingSettings } from './wing-chains.js';

export { SAMPLES };

const OPTIONS = [
  'sample', 'map', 'url', 'classify', 'seed', 'config', 'knowledge', 'autoplay', 'budgetMs', 'iterationsPerFrame',
  'stopWhenSettled', 'show', 'cloud', 'labels', 'graph', 'controls', 'wings', 'wasm', 'onUpdate', 'onError',
];
const STYLE_ID = 'ksmcmc-mount-style';
const CSS = `
.ksmcmc-mapper { font: 14px/1.4 system-ui, sans-serif; color: inherit; display: grid; gap: .5rem; max-width: 100%; }
.ksmcmc-mapper .ksmcmc-views { display: grid; grid-template-columns: minmax(0, 3fr) minmax(0, 1.4fr); gap: .5rem; align-items: start; }
.ksmcmc-mapper.ksmcmc-nograph .ksmcmc-views { grid-template-columns: minmax(0, 1fr); }
.ksmcmc-mapper canvas { width: 100%; height: auto; display: block; border: 1px solid #c8ccd2; border-radius: 3px; background: #fff; }
.ksmcmc-mapper .ksmcmc-map { image-rendering: pixelated; }
.ksmcmc-mapper .ksmcmc-map.ksmcmc-smooth { image-rendering: auto; }
.ksmcmc-mapper .ksmcmc-bar { display: flex; flex-wrap: wrap; gap: .4rem .8rem; align-items: center; }
.ksmcmc-mapper button { font: inherit; padding: .2rem .7rem; border: 1px solid #9aa1ab; border-radius: 3px; background: #f4f5f7; color: #1c1f23; cursor: pointer; }
.ksmcmc-mapper button:focus-visible, .ksmcmc-mapper input:focus-visible, .ksmcmc-mapper canvas:focus-visible { outline: 3px solid #f0a500; outline-offset: 2px; }
.ksmcmc-mapper label { display: inline-flex; gap: .3rem; align-items: center; }
.ksmcmc-mapper .ksmcmc-zoom { display: inline-flex; gap: .25rem; }
.ksmcmc-mapper .ksmcmc-zoom button { padding: .2rem .5rem; min-width: 2.2rem; }
.ksmcmc-mapper .ksmcmc-stats { font-variant-numeric: tabular-nums; opacity: .85; }
.ksmcmc-mapper .ksmcmc-error { color: #b00020; margin: 0; }
.ksmcmc-mapper .ksmcmc-error:empty { display: none; }
@media (max-width: 520px) { .ksmcmc-mapper .ksmcmc-views { grid-template-columns: minmax(0, 1fr); } }
`;

let initialised = null;

/**
 * Initialises the WebAssembly module once (later calls share the first one's promise).
 * @param {string | URL | Request | BufferSource | WebAssembly.Module} [wasm] where the .wasm
 *   is, if not next to ksmcmc.js
 */
export function ready(wasm) {
  initialised ??= init(wasm === undefined ? undefined : { module_or_path: wasm });
  return initialised;
}

/**
 * A further module of the package, imported and initialised the first time `load` is asked
 * for, then kept; a failed import is tried again the next time. (`load` is a literal
 * `import()`, which bundlers follow.)
 */
function lazyModule(load) {
  let module = null;
  return () =>
    (module ??= load().then(
      async (m) => {
        await m.default();
        return m;
      },
      (err) => {
        module = null;
        throw err;
      },
    ));
}

/** The synthetic generator's module (ksmcmc_synth.js and its .wasm beside it). */
const synthReady = lazyModule(() => import('./ksmcmc_synth.js'));
/** The plan module (ksmcmc_plan.js and its .wasm beside it): the wings' world. */
const planReady = lazyModule(() => import('./ksmcmc_plan.js'));

/**
 * A sample map, remade by the synthetic generator from its recipe: the same cells as the
 * repository's samples/NAME/map.pgm + map.yaml. Loads the generator's module the first time.
 * @param {string} name one of Object.keys(SAMPLES)
 * @returns {Promise<OccupancyMap>}
 */
export async function loadSample(name) {
  const { seed, config } = sampleRecipe(name);
  const [{ synth }] = await Promise.all([synthReady(), ready()]);
  const made = synth(seed, JSON.stringify(config));
  try {
    return OccupancyMap.fromYaml(made.mapYaml, made.mapPgm);
  } finally {
    made.free();
  }
}

/**
 * A map read from a file, classified by `rule`: 'auto' finds the background grays from the
 * histogram (as `ksmcmc floorplan` does to a PNG, a PGM or a map.yaml alike, so the same
 * pixels give the same cells), 'fixed' keeps the rule it was read with (the default
 * thresholds for a plain image, the map.yaml's own for a YAML).
 */
function classified(map, rule) {
  if (rule !== 'auto') return map;
  try {
    return map.reclassify('auto');
  } finally {
    map.free();
  }
}

/** Fetches a map: a PGM or PNG, or a map.yaml and the image it names (relative to it). */
async function fetchMap(url, rule) {
  const get = async (u) => {
    const r = await fetch(u);
    if (!r.ok) throw new Error(`${u}: ${r.status} ${r.statusText}`);
    return r;
  };
  const base = new URL(String(url), document.baseURI);
  if (!/\.ya?ml$/i.test(base.pathname)) {
    return classified(OccupancyMap.fromBytes(new Uint8Array(await (await get(base)).arrayBuffer())), rule);
  }
  const yaml = await (await get(base)).text();
  const m = /^\s*image\s*:\s*["']?([^"'#\r\n]+?)["']?\s*(#.*)?$/m.exec(yaml);
  if (!m) throw new Error(`${base}: no \`image:\` line, so it is not a ROS map.yaml`);
  const image = new Uint8Array(await (await get(new URL(m[1].trim(), base))).arrayBuffer());
  return classified(OccupancyMap.fromYaml(yaml, image), rule);
}

function checkOptions(options) {
  if (options === null || typeof options !== 'object') throw new Error('mount: options must be an object');
  for (const key of Object.keys(options)) {
    if (!OPTIONS.includes(key)) {
      throw new Error(`mount: unknown option ${JSON.stringify(key)}; the options are ${OPTIONS.join(', ')}`);
    }
  }
  const sources = ['sample', 'map', 'url'].filter((k) => options[k] !== undefined);
  if (sources.length > 1) throw new Error(`mount: give one of sample, map and url, not ${sources.join(' and ')}`);
  const { budgetMs = 8, iterationsPerFrame } = options;
  if (!(Number.isFinite(budgetMs) && budgetMs > 0 && budgetMs <= 1000)) {
    throw new Error(`mount: budgetMs ${budgetMs} must be a number of milliseconds above 0 and at most 1000`);
  }
  if (iterationsPerFrame !== undefined && !(Number.isInteger(iterationsPerFrame) && iterationsPerFrame >= 1 && iterationsPerFrame <= 1e6)) {
    throw new Error(`mount: iterationsPerFrame ${iterationsPerFrame} must be a whole number from 1 to 1000000`);
  }
  if (options.show !== undefined && !['current', 'best'].includes(options.show)) {
    throw new Error(`mount: show ${JSON.stringify(options.show)} must be 'current' or 'best'`);
  }
  if (options.classify !== undefined && !['auto', 'fixed'].includes(options.classify)) {
    throw new Error(`mount: classify ${JSON.stringify(options.classify)} must be 'auto' or 'fixed'`);
  }
  if (options.stopWhenSettled !== undefined && typeof options.stopWhenSettled !== 'boolean') {
    throw new Error(`mount: stopWhenSettled ${JSON.stringify(options.stopWhenSettled)} must be true or false`);
  }
  if (options.knowledge !== undefined && typeof options.knowledge !== 'boolean') {
    throw new Error(`mount: knowledge ${JSON.stringify(options.knowledge)} must be true or false`);
  }
  if (options.wings !== undefined && typeof options.wings !== 'boolean') {
    throw new Error(`mount: wings ${JSON.stringify(options.wings)} must be true or false`);
  }
}

/**
 * The chain settings as JSON text: `config` (an object or its text) with knowledge supervision
 * turned off when `knowledge` is false. Text that is not a JSON object goes to the chain as it
 * is, so that its own error names the problem.
 */
function chainSettings(config, knowledge) {
  const text = config === undefined || typeof config === 'string' ? config : JSON.stringify(config);
  if (knowledge !== false) return text;
  let settings = {};
  if (text?.trim()) {
    try {
      settings = JSON.parse(text);
    } catch {
      return text;
    }
  }
  if (settings === null || typeof settings !== 'object' || Array.isArray(settings)) return text;
  const k = typeof settings.knowledge === 'object' && settings.knowledge !== null ? settings.knowledge : {};
  return JSON.stringify({ ...settings, knowledge: { ...k, enabled: false } });
}

function el(tag, props = {}, children = []) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(props)) {
    if (k === 'class') e.className = v;
    else if (k.startsWith('aria-') || k === 'role' || k.startsWith('data-')) e.setAttribute(k, v);
    else e[k] = v;
  }
  e.append(...children);
  return e;
}

/**
 * Builds a live mapper inside `element` and resolves to its controller. See mount.d.ts for
 * the options and the controller.
 * @param {HTMLElement} element
 * @param {import('./mount.js').MountOptions} [options]
 * @returns {Promise<import('./mount.js').MapperWidget>}
 */
export async function mount(element, options = {}) {
  if (!(element instanceof Element)) throw new Error('mount: the first argument must be a DOM element');
  checkOptions(options);
  await ready(options.wasm);
  const { budgetMs = 8, iterationsPerFrame, labels = false, graph = true, controls = true } = options;
  let show = options.show ?? 'current';
  // Your own map is explained until it settles; a sample runs on (as on the live mapper page).
  const stopWhenSettled = options.stopWhenSettled ?? (options.map !== undefined || options.url !== undefined);
  let settledWhenStarted = false;
  let cloud = Boolean(options.cloud);
  const name = options.sample ?? (options.url !== undefined ? String(options.url).split('/').pop() : options.map ? 'map' : 'office-small');

  let map;
  let ownMap = true;
  if (options.map instanceof OccupancyMap) {
    map = options.map;
    ownMap = false;
  } else if (options.map && typeof options.map === 'object' && 'yaml' in options.map) {
    map = classified(
      OccupancyMap.fromYaml(String(options.map.yaml), new Uint8Array(options.map.image)),
      options.classify ?? 'auto',
    );
  } else if (options.map instanceof Uint8Array || options.map instanceof ArrayBuffer) {
    map = classified(OccupancyMap.fromBytes(new Uint8Array(options.map)), options.classify ?? 'auto');
  } else if (options.map !== undefined) {
    throw new Error('mount: map must be a Map, the bytes of a PGM or PNG, or { yaml, image }');
  } else if (options.url !== undefined) {
    map = await fetchMap(options.url, options.classify ?? 'auto');
  } else {
    map = await loadSample(options.sample ?? 'office-small');
  }
  const config = chainSettings(options.config, options.knowledge);
  let mapper;
  try {
    mapper = new Mapper(map, config, options.seed ?? 1);
  } finally {
    if (ownMap) map.free();
  }

  if (!document.getElementById(STYLE_ID)) {
    document.head.append(el('style', { id: STYLE_ID, textContent: CSS }));
  }
  const mapCanvas = el('canvas', {
    class: 'ksmcmc-map', tabIndex: 0, role: 'img',
    'aria-label': `Occupancy map ${name}, ${mapper.width} by ${mapper.height} cells, with the chain's world`,
  });
  const graphCanvas = el('canvas', { class: 'ksmcmc-graph', role: 'img', 'aria-label': 'Scene graph of the world' });
  const toggleButton = el('button', { type: 'button', textContent: 'Start', 'aria-keyshortcuts': 'Space' });
  const stepButton = el('button', { type: 'button', textContent: 'Step', 'aria-keyshortcuts': 'S' });
  const resetButton = el('button', { type: 'button', textContent: 'Reset', 'aria-keyshortcuts': 'R' });
  const cloudBox = el('input', { type: 'checkbox', checked: cloud });
  const bestBox = el('input', { type: 'checkbox', checked: show === 'best' });
  const statsLine = el('span', { class: 'ksmcmc-stats' });
  // The chain's picture at the zoom's detail, drawn on the map canvas through the view.
  const picture = document.createElement('canvas');
  let drawnScale = 0;
  const viewport = new Viewport(mapCanvas, {
    onChange: () => (running ? paint() : draw()),
    controls: controls ? { className: 'ksmcmc-zoom', label: 'Zoom the map' } : false,
  });
  const errorLine = el('p', { class: 'ksmcmc-error', role: 'alert' });
  const bar = el('div', { class: 'ksmcmc-bar' }, [
    toggleButton, stepButton, resetButton,
    el('label', {}, [cloudBox, 'posterior cloud']),
    el('label', {}, [bestBox, 'best world']),
    ...(viewport.controls ? [viewport.controls] : []),
    statsLine,
  ]);
  const root = el('div', { class: `ksmcmc-mapper${graph ? '' : ' ksmcmc-nograph'}`, role: 'group', 'aria-label': `Live mapper: ${name}` }, [
    el('div', { class: 'ksmcmc-views' }, graph ? [mapCanvas, graphCanvas] : [mapCanvas]),
    ...(controls ? [bar] : [statsLine]),
    errorLine,
  ]);
  element.replaceChildren(root);

  let running = false;
  let visible = true;
  let raf = 0;
  let destroyed = false;
  let lastStats = 0;
  let rate = { iteration: 0, time: performance.now(), perSecond: 0 };
  // The world of the building's wings (option `wings`) for the iteration it was made at, and
  // the wing whose chain runs now; `wingsRun` counts runs, so that a stale one stops.
  let wings = null;
  let wingRunning = null;
  let wingsFor = null;
  let wingsRun = 0;
  const wingsNow = () => (wings && wings.iteration === mapper.iteration ? wings : null);

  const stats = () => ({
    iteration: mapper.iteration,
    logPosterior: mapper.logPosterior,
    bestLogPosterior: mapper.bestLogPosterior,
    acceptance: mapper.acceptance,
    units: mapper.units,
    bestUnits: mapper.bestUnits,
    doors: mapper.doors,
    predictionRate: mapper.predictionRate,
    bestPredictionRate: mapper.bestPredictionRate,
    iterationsPerSecond: rate.perSecond,
    settledAt: mapper.settledAt ?? null,
    running,
    wings: wingsNow() && { count: wings.count, units: wings.units, predictionRate: wings.predictionRate },
  });

  const fail = (err) => {
    pause();
    errorLine.textContent = err instanceof Error ? err.message : String(err);
    options.onError?.(err);
  };

  // Enough pixels per cell for the screen (at most 3): shrunk smoothly, never blown up blurred.
  const scale = () => {
    const ratio = ((mapCanvas.clientWidth || mapper.width) * (globalThis.devicePixelRatio || 1)) / mapper.width;
    const s = Math.min(3, Math.max(1, Math.ceil(ratio - 0.01)));
    mapCanvas.classList.toggle('ksmcmc-smooth', s >= ratio);
    return s;
  };

  /** The picture, through the view, on a map canvas that holds the whole map at `s`. */
  const paint = (s = scale()) => {
    if (destroyed || !drawnScale) return;
    if (mapCanvas.width !== mapper.width * s || mapCanvas.height !== mapper.height * s) {
      mapCanvas.width = mapper.width * s;
      mapCanvas.height = mapper.height * s;
    }
    viewport.draw(mapCanvas, picture);
  };

  const draw = () => {
    if (destroyed) return;
    try {
      const s = scale();
      const v = viewport.view;
      // Zoomed in: more pixels per cell, but this draws on the page's thread in every frame:
      // at most 2 million pixels (a few milliseconds).
      const detail = v.isReset ? s : Math.max(s, detailScale(s, v.zoom, mapper.width * mapper.height, { maxScale: 6, maxPixels: 2_000_000 }));
      const world = show === 'best' ? wingsNow()?.world ?? undefined : undefined;
      // `labels` are the units' (the widget has no room layer): drawMapper's unitLabels.
      drawMapper(picture, mapper, { show, cloud, labels, unitLabels: labels, scale: detail, world });
      drawnScale = detail;
      paint(s);
      if (graph) {
        const dpr = globalThis.devicePixelRatio || 1;
        const w = Math.max(60, Math.round((graphCanvas.clientWidth || 240) * dpr));
        const h = Math.max(40, Math.round(w * Math.min(1.2, Math.max(0.4, mapper.height / mapper.width))));
        drawSceneGraph(graphCanvas, mapper, { show, width: w, height: h });
      }
    } catch (err) {
      fail(err);
      return;
    }
    const now = performance.now();
    if (now - rate.time >= 500) {
      rate = { iteration: mapper.iteration, time: now, perSecond: ((mapper.iteration - rate.iteration) * 1000) / (now - rate.time) };
    }
    if (now - lastStats >= 250 || !running) {
      lastStats = now;
      const s = stats();
      statsLine.textContent =
        `iteration ${s.iteration.toLocaleString('en-US')} · log p ${s.bestLogPosterior.toFixed(0)} · ` +
        `${s.bestUnits} units · K ${s.bestPredictionRate.toFixed(3)}` +
        (running ? ` · ${Math.round(s.iterationsPerSecond).toLocaleString('en-US')}/s` : '') +
        (s.settledAt !== null ? ` · settled at ${s.settledAt.toLocaleString('en-US')}` : '') +
        (wingRunning ? ` · wing ${wingRunning.wing} of ${wingRunning.of}: ${wingRunning.iteration.toLocaleString('en-US')}` : '') +
        (s.wings?.count ? ` · ${s.wings.count} wings: ${s.wings.units} units, K ${s.wings.predictionRate.toFixed(3)}` : '');
    }
    options.onUpdate?.(stats());
  };

  const schedule = () => {
    if (!raf && running && visible && !destroyed) raf = requestAnimationFrame(frame);
  };
  function frame() {
    raf = 0;
    if (!running || destroyed) return;
    try {
      if (iterationsPerFrame) mapper.step(iterationsPerFrame);
      else mapper.runFor(budgetMs);
    } catch (err) {
      fail(err);
      return;
    }
    if (stopWhenSettled && !settledWhenStarted && mapper.settledAt !== undefined) {
      pause();
      return;
    }
    draw();
    schedule();
  }

  /**
   * Explains a building of several wall directions wing by wing once the chain has stopped
   * (option `wings`), as `ksmcmc floorplan` does: a chain per wing on the wing's map, turned by
   * its direction, with the chain's seed and iterations, stepped in slices of about `budgetMs`
   * between frames; then their world, which the best-world view shows.
   */
  async function explainWings() {
    const target = mapper.iteration;
    if (!options.wings || destroyed || running || target === 0) return;
    // Done for this iteration, or under way (a second pause asks again).
    if (wings?.iteration === target || wingsFor === target) return;
    const run = ++wingsRun;
    wingsFor = target;
    const gone = () => destroyed || running || run !== wingsRun || mapper.iteration !== target;
    // The chain's own world stands for the building: one wing, or no wings to be had.
    const oneChain = () => ({ iteration: target, count: 0, world: null, units: mapper.bestUnits, predictionRate: mapper.bestPredictionRate });
    try {
      const x = await planReady();
      if (gone()) return;
      const map = mapper.map;
      let floor;
      try {
        floor = { pgm: map.toPgm(), yaml: map.toYaml('map.pgm') };
      } finally {
        map.free();
      }
      const input = mapper.planInput();
      const first = new x.Plan(floor.pgm, floor.yaml, input);
      let inputs;
      try {
        const settings = wingSettings(config);
        if (first.wingCount === 0 || settings === null) {
          wings = oneChain();
          return;
        }
        const onProgress = (p) => {
          wingRunning = p;
          draw();
        };
        inputs = await runWingChains({
          first, yaml: floor.yaml, config: settings, seed: mapper.seed, target, sliceMs: budgetMs, Map: OccupancyMap, Mapper, gone, onProgress,
        });
        if (inputs === null) return;
      } finally {
        first.free();
      }
      const made = new x.Plan(floor.pgm, floor.yaml, input, undefined, inputs);
      try {
        const report = JSON.parse(made.reportJson());
        wings = { iteration: target, count: inputs.length, world: made.worldJson(), units: report.units, predictionRate: report.cell_prediction_rate };
      } finally {
        made.free();
      }
    } catch (err) {
      if (!gone()) {
        // Not again for this iteration: failing pauses, and a pause explains the wings.
        wings = oneChain();
        fail(err);
      }
    } finally {
      if (run === wingsRun) {
        wingRunning = null;
        wingsFor = null;
      }
      if (!destroyed && !running) draw();
    }
  }

  function play() {
    if (destroyed || running) return;
    running = true;
    wingsRun++;
    wingRunning = null;
    wingsFor = null;
    settledWhenStarted = mapper.settledAt !== undefined;
    errorLine.textContent = '';
    toggleButton.textContent = 'Pause';
    rate = { iteration: mapper.iteration, time: performance.now(), perSecond: 0 };
    schedule();
  }
  function pause() {
    running = false;
    toggleButton.textContent = 'Start';
    if (raf) cancelAnimationFrame(raf);
    raf = 0;
    if (!destroyed) draw();
    explainWings();
  }
  const toggle = () => (running ? pause() : play());
  function step(n = iterationsPerFrame ?? 500) {
    try {
      mapper.step(n);
    } catch (err) {
      fail(err);
      return;
    }
    draw();
    if (!running) explainWings();
  }
  function reset(seed) {
    try {
      mapper.reset(seed);
    } catch (err) {
      fail(err);
      return;
    }
    wings = null;
    wingsRun++;
    wingRunning = null;
    wingsFor = null;
    errorLine.textContent = '';
    rate = { iteration: 0, time: performance.now(), perSecond: 0 };
    draw();
  }

  toggleButton.addEventListener('click', toggle);
  stepButton.addEventListener('click', () => step());
  resetButton.addEventListener('click', () => reset());
  cloudBox.addEventListener('change', () => {
    cloud = cloudBox.checked;
    if (!running) draw();
  });
  bestBox.addEventListener('change', () => {
    show = bestBox.checked ? 'best' : 'current';
    if (!running) draw();
  });
  mapCanvas.addEventListener('keydown', (e) => {
    if (e.ctrlKey || e.metaKey || e.altKey) return;
    const key = e.key.toLowerCase();
    if (key === ' ') toggle();
    else if (key === 's') step();
    else if (key === 'r') reset();
    else return;
    e.preventDefault();
  });

  // Run only while on screen: a documentation page may hold several widgets.
  const observer = typeof IntersectionObserver === 'function'
    ? new IntersectionObserver((entries) => {
      visible = entries.some((e) => e.isIntersecting);
      schedule();
    })
    : null;
  observer?.observe(root);
  const resized = typeof ResizeObserver === 'function' ? new ResizeObserver(() => running || draw()) : null;
  resized?.observe(root);

  draw();
  const reduced = globalThis.matchMedia?.('(prefers-reduced-motion: reduce)').matches;
  if (options.autoplay === 'always' || (options.autoplay && !reduced)) play();

  return {
    element: root,
    mapper,
    get running() {
      return running;
    },
    play,
    pause,
    toggle,
    step,
    reset,
    stats,
    redraw: draw,
    get view() {
      return viewport.view.state();
    },
    resetView: () => viewport.reset(),
    destroy() {
      if (destroyed) return;
      wingsRun++;
      destroyed = true;
      running = false;
      if (raf) cancelAnimationFrame(raf);
      observer?.disconnect();
      resized?.disconnect();
      viewport.destroy();
      root.remove();
      mapper.free();
    },
  };
}
