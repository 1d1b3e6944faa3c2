// Shared set-up for the browser tests: paths, the native CLI, the server and Chromium.

import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { existsSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { serve } from './server.mjs';

export const REPO = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
export const WWW = join(REPO, 'www');
/** The native CLI, built by `make cli` (cargo build --bin ksmcmc). */
export const CLI = join(REPO, 'target/debug/ksmcmc');
/** Benchmark maps; the repository is checked out beside shared/. */
export const DATASETS = resolve(REPO, '../shared/datasets');
export const CHROMIUM = process.env.CHROMIUM ?? '/usr/bin/chromium';

const CHROMIUM_ARGS = [
  '--no-sandbox',
  '--disable-gpu',
  // WebGL (the mapper's 3D view) on the CPU: SwiftShader, which newer Chromium uses only when
  // asked.
  '--enable-unsafe-swiftshader',
  '--disable-dev-shm-usage',
  '--disable-background-networking',
  '--disable-component-update',
  '--disable-sync',
  '--no-first-run',
];

/** Runs the native CLI; throws with its stderr if it fails. */
export function cli(...args) {
  if (!existsSync(CLI)) throw new Error(`${CLI} is missing: build it with \`make cli\``);
  const r = spawnSync(CLI, args, { encoding: 'utf8' });
  if (r.status !== 0) {
    throw new Error(`ksmcmc ${args.join(' ')} exited with ${r.status}: ${r.stderr.trim()}`);
  }
  return r.stdout;
}

/** Size and class counts of a map file, as the native loader sees them (`ksmcmc info`). */
export function nativeInfo(path) {
  const out = cli('info', path);
  const size = / (\d+) x (\d+) cells/.exec(out);
  const count = (name) => Number(new RegExp(`^\\s+${name}\\s+(\\d+)`, 'm').exec(out)?.[1]);
  if (!size) throw new Error(`unexpected \`ksmcmc info\` output:\n${out}`);
  return {
    width: Number(size[1]),
    height: Number(size[2]),
    free: count('free'),
    unknown: count('unknown'),
    occupied: count('occupied'),
  };
}

/** Starts the server and the browser once for a test file. */
export async function startBrowser() {
  if (!existsSync(join(WWW, 'pkg/ksmcmc_bg.wasm'))) {
    throw new Error('www/pkg is missing: build it with `make www-pkg`');
  }
  if (!existsSync(CHROMIUM)) throw new Error(`${CHROMIUM} is missing: \`make browser-tools\` installs it`);
  const server = await serve(WWW);
  const browser = await chromium.launch({ executablePath: CHROMIUM, args: CHROMIUM_ARGS });
  return {
    server,
    browser,
    async close() {
      await browser.close();
      await server.close();
    },
  };
}

/**
 * Opens the Maps page in a fresh context and waits until the wasm module is ready. Records
 * console errors and page errors in `page.problems`.
 */
export async function openPage(env, path = 'index.html', viewport = { width: 1280, height: 900 }) {
  const context = await env.browser.newContext({ acceptDownloads: true, viewport });
  const page = await context.newPage();
  page.problems = [];
  page.on('console', (m) => {
    if (m.type() === 'error') page.problems.push(`console.error: ${m.text()}`);
  });
  page.on('pageerror', (e) => page.problems.push(`page error: ${e.message}`));
  page.on('requestfailed', (r) => page.problems.push(`request failed: ${r.url()} ${r.failure()?.errorText}`));
  await page.goto(env.server.url + path);
  await page.waitForFunction(() => document.documentElement.dataset.state !== 'loading', null, { timeout: 60_000 });
  const state = await page.evaluate(() => document.documentElement.dataset.state);
  if (state !== 'ready') {
    const msg = await page.textContent('#message-text');
    throw new Error(`the page did not get ready (${state}): ${msg}; ${page.problems.join('; ')}`);
  }
  return page;
}

/** What the map canvas shows: its size and its pixels by class (dark, mid gray, light). */
export function canvasClasses(page) {
  return page.evaluate(() => {
    const c = document.getElementById('map');
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    let occupied = 0;
    let unknown = 0;
    let free = 0;
    for (let i = 0; i < d.length; i += 4) {
      const lum = (d[i] + d[i + 1] + d[i + 2]) / 3;
      if (lum < 64) occupied++;
      else if (lum > 240) free++;
      else unknown++;
    }
    const box = c.getBoundingClientRect();
    return { width: c.width, height: c.height, free, unknown, occupied, shown: { width: box.width, height: box.height } };
  });
}

/** The class counts the page shows (digits of the counts list). */
export async function shownCounts(page) {
  const num = async (id) => Number((await page.textContent(id)).split('(')[0].replace(/\D/g, ''));
  return {
    free: await num('#count-free'),
    unknown: await num('#count-unknown'),
    occupied: await num('#count-occupied'),
  };
}

/** Clicks a download button and returns the file's name and bytes. */
export async function download(page, selector) {
  const [dl] = await Promise.all([page.waitForEvent('download'), page.click(selector)]);
  const path = await dl.path();
  const { readFile } = await import('node:fs/promises');
  return { name: dl.suggestedFilename(), bytes: await readFile(path) };
}

/** An 8-bit binary PGM. */
export function pgm(width, height, samples) {
  return Buffer.concat([Buffer.from(`P5\n${width} ${height}\n255\n`), Buffer.from(samples)]);
}

/** A 16-bit binary PGM (e.g. `labels.pgm`) as { width, height, values }. */
export function readPgm16(bytes) {
  const text = Buffer.from(bytes.subarray(0, 40)).toString('latin1');
  const m = /^P5\s+(\d+)\s+(\d+)\s+(\d+)\s/.exec(text);
  assert.ok(m, `not a PGM: ${text}`);
  const [width, height] = [Number(m[1]), Number(m[2])];
  const data = bytes.subarray(m[0].length);
  const values = new Uint16Array(width * height);
  for (let i = 0; i < values.length; i++) values[i] = (data[2 * i] << 8) | data[2 * i + 1];
  return { width, height, values };
}

/** Fails on console errors and uncaught exceptions, then closes the page. */
export async function done(page) {
  const problems = page.problems;
  await page.context().close();
  assert.deepEqual(problems, [], 'the page logged errors');
}

/** The numbers of a page that exposes `window.__ksmcmc.snapshot()` (the mapper, the table-top). */
export const snap = (page) => page.evaluate(() => window.__ksmcmc.snapshot());

/** Waits until `predicate(snapshot, arg)` holds; on timeout fails with the last snapshot. */
export async function until(page, predicate, arg, timeout = 20_000) {
  try {
    await page.waitForFunction(([src, a]) => new Function('s', 'a', `return (${src})(s, a)`)(window.__ksmcmc.snapshot(), a), [predicate.toString(), arg], { timeout });
  } catch (err) {
    assert.fail(`waited for ${predicate} (${JSON.stringify(arg)}): ${err.message.split('\n')[0]}; the page is at ${JSON.stringify(await snap(page))}`);
  }
}
