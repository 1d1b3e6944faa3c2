// The pages' soak test (`make soak`, not in CI): drives the live mapper and the table-top page
// in headless Chromium for a long time with random but seeded actions (paint strokes, uploads
// of valid and corrupted files, resets, knowledge on and off, start and pause) and records the
// wasm heap and the JS heap every minute.
//
//   node scripts/soak.mjs [--minutes 30] [--seed 1] [--page mapper|tabletop|both] [--out FILE]
//
// Fails (exit 1) on any uncaught error or console error in a page or its workers, on a message
// that says the module panicked, or when a wasm heap grows by more than 10 % after the first
// five minutes (wasm memory only grows, so growth there is a leak or an unbounded cache).
// The two pages run side by side in one browser. Needs `make www-pkg` and the e2e packages.

import { readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { parseArgs } from 'node:util';
import { REPO, openPage, pgm, startBrowser } from '../tests/e2e/harness.mjs';

const { values: opts } = parseArgs({
  options: {
    minutes: { type: 'string', default: '30' },
    seed: { type: 'string', default: '1' },
    page: { type: 'string', default: 'both' },
    out: { type: 'string' },
  },
});
const MINUTES = Number(opts.minutes);
const WARMUP_MIN = Math.min(5, MINUTES / 2);
const MAX_GROWTH = 0.1;

/** A small seeded generator (mulberry32), so a failing run can be repeated. */
function rng(seed) {
  let a = seed >>> 0;
  return () => {
    a = (a + 0x6d2b79f5) >>> 0;
    let t = a;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
const mib = (bytes) => Math.round((bytes / 1048576) * 10) / 10;

/** Every sample map, as files the mapper's file input takes. */
function sampleMaps() {
  const names = ['office-small', 'furnished', 'two-corridors', 'partial', 'office-rotated', 'building-large'];
  return names.map((n) => ({ name: `${n}.pgm`, mimeType: 'image/x-portable-graymap', buffer: readFileSync(join(REPO, 'samples', n, 'map.pgm')) }));
}

/** A corrupted map: truncated, a lying header, random bytes, or a PNG that is not one. */
function corrupted(rand, maps) {
  const base = maps[Math.floor(rand() * maps.length)].buffer;
  switch (Math.floor(rand() * 5)) {
    case 0:
      return { name: 'truncated.pgm', mimeType: 'image/x-portable-graymap', buffer: base.subarray(0, Math.floor(base.length * rand())) };
    case 1:
      return { name: 'huge.pgm', mimeType: 'image/x-portable-graymap', buffer: Buffer.from('P5\n60000 60000\n255\n') };
    case 2: {
      const b = Buffer.from(base);
      for (let i = 0; i < 64; i++) b[Math.floor(rand() * b.length)] = Math.floor(rand() * 256);
      return { name: 'flipped.pgm', mimeType: 'image/x-portable-graymap', buffer: b };
    }
    case 3:
      return { name: 'noise.png', mimeType: 'image/png', buffer: Buffer.from(Array.from({ length: 4096 }, () => Math.floor(rand() * 256))) };
    default:
      return { name: 'tiny.pgm', mimeType: 'image/x-portable-graymap', buffer: pgm(2, 2, [0, 254, 205, 0]) };
  }
}

/** Problems no run may have: uncaught errors, console errors, panics shown to the user. */
function watch(page, label, problems) {
  const note = (text) => problems.push(`${label}: ${text}`);
  page.on('console', (m) => m.type() === 'error' && note(`console.error: ${m.text()}`));
  page.on('pageerror', (e) => note(`page error: ${e.message}`));
  page.on('worker', (w) => {
    if (typeof w.on === 'function') w.on('console', (m) => m.type() === 'error' && note(`worker console.error: ${m.text()}`));
  });
}

/** Dismisses the alert if it is still up (the page may have cleared it meanwhile). */
function dismiss(page) {
  return page.evaluate(() => {
    if (!document.getElementById('message').hidden) document.getElementById('message-close').click();
  });
}

async function shownError(page) {
  return page.evaluate(() => (document.getElementById('message').hidden ? '' : document.getElementById('message-text').textContent));
}

/**
 * After an action: reads and dismisses the alert it raised, and starts the chain again unless
 * it runs or `keepPaused` (pages are soaked mostly running). Returns the action and the alert.
 */
async function afterAction(page, pick, keepPaused) {
  const msg = await shownError(page);
  if (msg) await dismiss(page);
  const s = await page.evaluate(() => window.__ksmcmc.snapshot());
  if (!s.running && !keepPaused && (await page.isEnabled('#run'))) await page.click('#run');
  return { pick, msg };
}

/** One random action on the mapper page. */
async function mapperAction(page, rand, maps, step) {
  const pick = step < maps.length ? 'upload' : ['paint', 'upload', 'corrupt', 'reset', 'knowledge', 'pause'][Math.floor(rand() * 6)];
  switch (pick) {
    case 'upload':
      await page.setInputFiles('#file', maps[step < maps.length ? step : Math.floor(rand() * maps.length)]);
      break;
    case 'corrupt':
      await page.setInputFiles('#file', corrupted(rand, maps));
      break;
    case 'paint': {
      await page.keyboard.press('Escape');
      if (!(await page.isChecked('#paint'))) await page.click('#paint');
      await page.locator('#map').scrollIntoViewIfNeeded();
      const box = await page.locator('#map').boundingBox();
      const at = () => [box.x + rand() * box.width, box.y + rand() * box.height];
      const [x0, y0] = at();
      const [x1, y1] = at();
      await page.mouse.move(x0, y0);
      await page.mouse.down();
      await page.mouse.move(x1, y1, { steps: 8 });
      await page.mouse.up();
      await page.click('#paint');
      break;
    }
    case 'reset':
      await page.click('#reset');
      break;
    case 'knowledge':
      await page.click('#knowledge');
      await page.click('#reset');
      break;
    default:
      if (await page.isEnabled('#run')) await page.click('#run');
  }
  return afterAction(page, pick, pick === 'pause');
}

/** One random action on the table-top page. */
async function tabletopAction(page, rand, step) {
  const pick = ['generate', 'corrupt', 'reset', 'rules', 'run'][Math.floor(rand() * 5)];
  switch (pick) {
    case 'generate':
      await page.fill('#synth-seed', String(Math.floor(rand() * 1000)));
      await page.fill('#synth-objects', String(1 + Math.floor(rand() * 20)));
      await page.click('#generate');
      break;
    case 'corrupt': {
      const text = await page.evaluate(() => window.__ksmcmc.sceneText());
      const cut = text.slice(0, Math.floor(text.length * rand()));
      await page.setInputFiles('#file', { name: 'scene.json', mimeType: 'application/json', buffer: Buffer.from(step % 2 ? cut : '{"objects": 7}') });
      break;
    }
    case 'reset':
      await page.click('#reset');
      break;
    case 'rules':
      await page.click(rand() < 0.5 ? '#rules-default' : '#rules-apply');
      break;
    default:
      if (await page.isEnabled('#run')) await page.click('#run');
  }
  return afterAction(page, pick, false);
}

async function heaps(page, kind) {
  const js = await page.evaluate(() => performance.memory?.usedJSHeapSize ?? NaN);
  const wasm = kind === 'mapper' ? (await page.evaluate(() => window.__ksmcmc.heap())).chain : await page.evaluate(() => window.__ksmcmc.heap());
  return { wasm, js };
}

/** Soaks one page for MINUTES; returns its per-minute samples, action counts and problems. */
async function soak(env, kind, seed) {
  const problems = [];
  const page = await openPage(env, kind === 'mapper' ? 'mapper.html' : 'tabletop.html');
  watch(page, kind, problems);
  const rand = rng(seed);
  const maps = sampleMaps();
  const samples = [];
  const actions = {};
  const panics = [];
  const grew = [];
  let peak = (await heaps(page, kind)).wasm;
  const start = Date.now();
  let nextSample = start;
  for (let step = 0; Date.now() - start < MINUTES * 60_000; step++) {
    if (Date.now() >= nextSample) {
      const h = await heaps(page, kind);
      samples.push({ minute: Math.round((Date.now() - start) / 60_000), wasm_mib: mib(h.wasm), js_mib: mib(h.js) });
      console.log(`${kind} ${samples.at(-1).minute} min: wasm ${samples.at(-1).wasm_mib} MiB, JS ${samples.at(-1).js_mib} MiB, ${step} actions`);
      nextSample += 60_000;
    }
    const { pick, msg } = kind === 'mapper' ? await mapperAction(page, rand, maps, step) : await tabletopAction(page, rand, step);
    actions[pick] = (actions[pick] ?? 0) + 1;
    // Which action made the wasm heap grow, for whoever has to find out why.
    const now = (await heaps(page, kind)).wasm;
    if (now > peak) {
      console.log(`${kind}: wasm heap ${mib(peak)} -> ${mib(now)} MiB after ${pick} (action ${step + 1})`);
      grew.push({ step: step + 1, action: pick, wasm_mib: mib(now) });
      peak = now;
    }
    if (/panick|unreachable|RuntimeError/i.test(msg)) panics.push(msg);
    await sleep(500 + rand() * 2500);
  }
  const h = await heaps(page, kind);
  samples.push({ minute: MINUTES, wasm_mib: mib(h.wasm), js_mib: mib(h.js) });
  await page.context().close();
  return { page: kind, samples, actions, grew, problems: [...problems, ...panics.map((p) => `${kind}: panic shown: ${p}`)] };
}

/** The wasm heap's growth after the warm-up: the last sample over the first after WARMUP_MIN. */
function growth(samples) {
  const base = samples.find((s) => s.minute >= WARMUP_MIN) ?? samples[0];
  const last = samples.at(-1);
  return { from_mib: base.wasm_mib, to_mib: last.wasm_mib, growth: (last.wasm_mib - base.wasm_mib) / base.wasm_mib };
}

const env = await startBrowser();
let results;
try {
  const kinds = opts.page === 'both' ? ['mapper', 'tabletop'] : [opts.page];
  results = await Promise.all(kinds.map((k, i) => soak(env, k, Number(opts.seed) + i)));
} finally {
  await env.close();
}
let failed = false;
for (const r of results) {
  r.wasm_growth = growth(r.samples);
  const pct = (r.wasm_growth.growth * 100).toFixed(1);
  console.log(`${r.page}: ${MINUTES} min, actions ${JSON.stringify(r.actions)}, wasm heap ${r.wasm_growth.from_mib} -> ${r.wasm_growth.to_mib} MiB after minute ${WARMUP_MIN} (${pct} %), ${r.problems.length} problems`);
  for (const p of r.problems) console.log(`  ${p}`);
  if (r.problems.length > 0 || r.wasm_growth.growth > MAX_GROWTH) failed = true;
}
if (opts.out) writeFileSync(opts.out, `${JSON.stringify({ minutes: MINUTES, seed: Number(opts.seed), results }, null, 2)}\n`);
console.log(failed ? 'soak: FAILED' : 'soak: passed');
process.exit(failed ? 1 : 0);
