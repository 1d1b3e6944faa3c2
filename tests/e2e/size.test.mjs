// What the pages download of the WebAssembly package (issue 12: the live mapper loads at most
// 500 kB of gzipped wasm before its first frame). The package is split into modules
// (src/wasm/mod.rs); each page loads the ones it needs, and the live mapper loads the plan
// module (rooms, exports, routes) only once its chain has found units. Sizes are the files'
// `gzip -9` sizes, as BENCHMARKS.md and `make pkg` count them.

import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { gzipSync } from 'node:zlib';
import { WWW, snap, startBrowser, until } from './harness.mjs';

/** The most the live mapper may load before its first frame, gzipped (issue 12). */
const MAPPER_LIMIT = 500_000;

let env;
before(async () => {
  env = await startBrowser();
});
after(async () => {
  await env?.close();
});

const gzipped = (file) => gzipSync(readFileSync(join(WWW, 'pkg', file)), { level: 9 }).length;

/**
 * Opens `path` and records the .wasm files its page and workers fetch until it is ready and
 * idle, then runs `then(page)`. Returns the page, its problems and the files loaded (a Set the
 * page keeps filling).
 */
async function open(path) {
  const context = await env.browser.newContext({ viewport: { width: 1280, height: 900 } });
  const wasm = new Set();
  const problems = [];
  context.on('response', (r) => {
    const name = new URL(r.url()).pathname.split('/').pop();
    if (name.endsWith('.wasm')) wasm.add(name);
    if (r.status() >= 400) problems.push(`${r.status()}: ${r.url()}`);
  });
  const page = await context.newPage();
  page.on('pageerror', (e) => problems.push(`page error: ${e.message}`));
  await page.goto(env.server.url + path);
  await page.waitForFunction(() => document.documentElement.dataset.state !== 'loading', null, { timeout: 60_000 });
  assert.equal(await page.evaluate(() => document.documentElement.dataset.state), 'ready', `${path} got ready`);
  return { page, wasm, problems };
}

test('the live mapper loads only the mapper module, under 500 kB gzipped, until its chain finds units', async (t) => {
  const { page, wasm, problems } = await open('mapper.html');
  await page.evaluate(() => window.__ksmcmc.idle());
  // The first frame is drawn, the rooms asked for: still the mapper module alone.
  await until(page, (s) => s.width > 0 && s.iteration === 0);
  await page.waitForTimeout(500);
  assert.deepEqual([...wasm], ['ksmcmc_bg.wasm'], 'what the page and its worker fetch before Start');
  const size = gzipped('ksmcmc_bg.wasm');
  t.diagnostic(`mapper page, first load: ksmcmc_bg.wasm ${size} bytes gzipped`);
  assert.ok(size <= MAPPER_LIMIT, `ksmcmc_bg.wasm is ${size} bytes gzipped, over ${MAPPER_LIMIT}`);

  // Start: once the best world has units, the worker loads the plan module for its rooms.
  await page.keyboard.press('Space');
  await until(page, (s) => s.bestUnits > 0, undefined, 60_000);
  await page.waitForFunction(() => Number(document.getElementById('stats').dataset.rooms) > 0, null, { timeout: 60_000 });
  assert.ok(wasm.has('ksmcmc_plan_bg.wasm'), `the plan module is loaded for the rooms: ${[...wasm]}`);
  assert.equal(wasm.has('ksmcmc_rules_bg.wasm') || wasm.has('ksmcmc_synth_bg.wasm') || wasm.has('ksmcmc_tabletop_bg.wasm'), false, [...wasm].join(', '));
  t.diagnostic(`then ksmcmc_plan_bg.wasm ${gzipped('ksmcmc_plan_bg.wasm')} bytes gzipped`);
  assert.ok((await snap(page)).running);
  await page.context().close();
  assert.deepEqual(problems, []);
});

test('each page loads the modules it needs and no other', async (t) => {
  const pages = {
    'index.html': ['ksmcmc_bg.wasm', 'ksmcmc_synth_bg.wasm'],
    'tabletop.html': ['ksmcmc_tabletop_bg.wasm'],
    'prior.html': ['ksmcmc_rules_bg.wasm'],
    'rules.html': ['ksmcmc_bg.wasm', 'ksmcmc_rules_bg.wasm'],
    'embed.html': ['ksmcmc_bg.wasm', 'ksmcmc_synth_bg.wasm'],
    // The robot (`Explorer`) and the chain it hands maps to are one module of their own, so
    // that the mapper module the other pages load first does not carry the robot.
    'explore.html': ['ksmcmc_explore_bg.wasm'],
  };
  // What a page may load besides, once its chain has a world: the rules page lists the best
  // world's placeholders, which the plan module's room layer finds, so on a fast machine the
  // plan module may come within the half second below.
  const later = { 'rules.html': ['ksmcmc_plan_bg.wasm'] };
  for (const [path, want] of Object.entries(pages)) {
    const { page, wasm, problems } = await open(path);
    await page.waitForTimeout(500);
    const fetched = [...wasm].filter((f) => !(later[path] ?? []).includes(f));
    assert.deepEqual(fetched.sort(), want.sort(), `${path} fetches`);
    const total = want.reduce((sum, f) => sum + gzipped(f), 0);
    t.diagnostic(`${path}: ${want.join(' + ')}, ${total} bytes gzipped`);
    await page.context().close();
    assert.deepEqual(problems, [], path);
  }
});
