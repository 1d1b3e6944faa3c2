// The embed as a reader of pkg/README.md uses it: a plain HTML page (no bundler) with the
// README's snippet, verbatim, next to the package where `npm install ksmcmc` puts it
// (node_modules/ksmcmc, here a copy of pkg/). And mount()'s map options: plain images are
// classified as `ksmcmc floorplan` classifies them unless told otherwise.

import { after, before, describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { copyFileSync, cpSync, existsSync, mkdirSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { chromium } from 'playwright-core';
import { CHROMIUM, DATASETS, REPO, cli } from './harness.mjs';
import { serve } from './server.mjs';

const LAB_A = join(DATASETS, 'bormann2016/lab_a_scan.png');

/** The first ```html block of pkg/README.md: the plain-page embed. */
function readmeSnippet() {
  const readme = readFileSync(join(REPO, 'pkg/README.md'), 'utf8');
  const m = /^```html\n([\s\S]*?)^```$/m.exec(readme);
  assert.ok(m, 'pkg/README.md has an ```html block');
  return m[1];
}

let site;
let server;
let browser;
before(async () => {
  if (!existsSync(join(REPO, 'pkg/ksmcmc_bg.wasm'))) throw new Error('pkg/ is not built: `make pkg`');
  site = mkdtempSync(join(tmpdir(), 'ksmcmc-embed-'));
  mkdirSync(join(site, 'node_modules'));
  cpSync(join(REPO, 'pkg'), join(site, 'node_modules/ksmcmc'), { recursive: true });
  writeFileSync(join(site, 'index.html'), readmeSnippet());
  if (existsSync(LAB_A)) copyFileSync(LAB_A, join(site, 'lab_a_scan.png'));
  server = await serve(site);
  browser = await chromium.launch({ executablePath: CHROMIUM, args: ['--no-sandbox', '--disable-gpu', '--disable-dev-shm-usage'] });
});
after(async () => {
  await browser?.close();
  await server?.close();
  if (site) rmSync(site, { recursive: true, force: true });
});

async function open() {
  const context = await browser.newContext({ viewport: { width: 1000, height: 800 } });
  const page = await context.newPage();
  page.problems = [];
  // The browser asks for /favicon.ico, which the snippet (rightly) does not provide: failed
  // loads are checked by URL, not by their console line.
  page.on('console', (m) => {
    if (m.type() === 'error' && !m.text().startsWith('Failed to load resource')) page.problems.push(`console.error: ${m.text()}`);
  });
  page.on('response', (r) => {
    if (r.status() >= 400 && new URL(r.url()).pathname !== '/favicon.ico') page.problems.push(`${r.status()}: ${r.url()}`);
  });
  page.on('pageerror', (e) => page.problems.push(`page error: ${e.message}`));
  page.on('requestfailed', (r) => page.problems.push(`request failed: ${r.url()}`));
  await page.goto(server.url);
  return page;
}

/** `report.json` of `ksmcmc floorplan ARGS... --out site/NAME`. */
function nativeReport(name, ...args) {
  const out = join(site, name);
  cli('floorplan', ...args, '--out', out);
  return JSON.parse(readFileSync(join(out, 'report.json'), 'utf8'));
}

/** Mounts a widget with `options` in a new element of the snippet's page, as `window[name]`. */
async function mountAs(page, name, options) {
  await page.waitForSelector('#demo .ksmcmc-mapper');
  await page.evaluate(async ([name, options]) => {
    const { mount } = await import('./node_modules/ksmcmc/mount.js');
    const div = document.body.appendChild(document.createElement('div'));
    window[name] = await mount(div, options);
  }, [name, options]);
}

describe('The embed as pkg/README.md shows it', () => {
  test('the package ships every module its modules import', () => {
    const json = JSON.parse(readFileSync(join(REPO, 'pkg/package.json'), 'utf8'));
    const shipped = json.files.filter((f) => f.endsWith('.js'));
    assert.ok(shipped.includes('mount.js') && shipped.includes('viewport.js'), JSON.stringify(json.files));
    for (const f of shipped) {
      const text = readFileSync(join(REPO, 'pkg', f), 'utf8');
      for (const [, spec] of text.matchAll(/^\s*import\b[^'"]*['"](\.\/[^'"]+)['"]/gm)) {
        assert.ok(json.files.includes(spec.slice(2)), `${f} imports ${spec}, which package.json's files leave out`);
      }
    }
  });

  test('the plain HTML snippet, verbatim, runs a live mapper', async () => {
    const page = await open();
    try {
      await page.waitForSelector('#demo .ksmcmc-mapper canvas.ksmcmc-map', { timeout: 30_000 });
      // autoplay: the statistics line counts iterations.
      await page.waitForFunction(
        () => Number(/iteration ([\d,]+)/.exec(document.querySelector('#demo .ksmcmc-stats')?.textContent ?? '')?.[1].replace(/,/g, '')) > 1000,
        null,
        { timeout: 30_000 },
      );
      assert.equal(await page.textContent('#demo button >> nth=0'), 'Pause', 'running');
      assert.deepEqual(page.problems, []);
    } finally {
      await page.context().close();
    }
  });

  test('mount({ stopWhenSettled }) pauses where `ksmcmc floorplan --until-settled` stops', async () => {
    const native = nativeReport('settled', join(REPO, 'samples/office-small/map.yaml'), '--until-settled', '--iterations', '1000000');
    const page = await open();
    try {
      await mountAs(page, '__settling', { sample: 'office-small', stopWhenSettled: true, autoplay: 'always' });
      await page.waitForFunction(() => !window.__settling.running, null, { timeout: 120_000 });
      const s = await page.evaluate(() => window.__settling.stats());
      assert.equal(s.settledAt, native.settled_at, 'settled at the iteration the CLI stops at');
      assert.ok(s.iteration >= s.settledAt && s.iteration < s.settledAt + 5000, `paused soon after: ${s.iteration}`);
      assert.match(await page.evaluate(() => window.__settling.element.textContent), /settled at [\d,]+/);
      // Start runs on.
      await page.evaluate(() => window.__settling.play());
      await page.waitForFunction((it) => window.__settling.stats().iteration > it + 500, s.iteration);
      assert.equal(await page.evaluate(() => window.__settling.running), true);
      assert.deepEqual(page.problems, []);
    } finally {
      await page.context().close();
    }
  });

  test('mount({ wings: true }) explains the two-wings sample wing by wing, as `ksmcmc floorplan` does', async () => {
    const native = nativeReport('wings', join(REPO, 'samples/two-wings/map.yaml'), '--iterations', '2000', '--seed', '3');
    assert.equal(native.wings.length, 2, 'the CLI explains the sample with a chain per wing');
    const page = await open();
    try {
      await mountAs(page, '__wings', { sample: 'two-wings', seed: 3, wings: true, show: 'best' });
      await page.evaluate(() => window.__wings.step(2000));
      await page.waitForFunction(() => window.__wings.stats().wings !== null, null, { timeout: 120_000 });
      const s = await page.evaluate(() => window.__wings.stats());
      assert.equal(s.iteration, 2000);
      assert.deepEqual(s.wings, { count: 2, units: native.units, predictionRate: native.cell_prediction_rate });
      assert.ok(s.wings.predictionRate > s.bestPredictionRate, `the wings' K ${s.wings.predictionRate} over one chain's ${s.bestPredictionRate}`);
      assert.match(await page.evaluate(() => window.__wings.element.textContent), /2 wings: \d+ units, K 0\.\d{3}/);
      // Running on drops the wings' world; stopping again explains the wings of the new iteration.
      await page.evaluate(() => window.__wings.step(500));
      assert.equal(await page.evaluate(() => window.__wings.stats().wings), null);
      await page.waitForFunction(() => window.__wings.stats().wings?.count === 2, null, { timeout: 120_000 });
      const bad = await page.evaluate(async () => {
        const { mount } = await import('./node_modules/ksmcmc/mount.js');
        try {
          await mount(document.createElement('div'), { wings: 'yes' });
        } catch (e) {
          return e.message;
        }
        return null;
      });
      assert.match(bad, /wings "yes" must be true or false/);
      assert.deepEqual(page.problems, []);
    } finally {
      await page.context().close();
    }
  });

  test('mount() classifies plain images as the CLI does (auto) unless told otherwise, and takes knowledge', async (t) => {
    const page = await open();
    try {
      await page.waitForSelector('#demo .ksmcmc-mapper');
      const knowledge = await page.evaluate(async () => {
        const { mount } = await import('./node_modules/ksmcmc/mount.js');
        const div = document.body.appendChild(document.createElement('div'));
        const out = [];
        for (const options of [{}, { knowledge: false }, { knowledge: false, config: { posterior: { temperature: 2 } } }]) {
          const w = await mount(div, { sample: 'office-small', ...options });
          const r = JSON.parse(w.mapper.planInput());
          out.push(r.knowledge);
          w.destroy();
        }
        try {
          await mount(div, { knowledge: 'yes' });
        } catch (e) {
          out.push(e.message);
        }
        try {
          await mount(div, { classify: 'otsu' });
        } catch (e) {
          out.push(e.message);
        }
        div.remove();
        return out;
      });
      assert.deepEqual(knowledge.slice(0, 3), [true, false, false]);
      assert.match(knowledge[3], /knowledge "yes" must be true or false/);
      assert.match(knowledge[4], /classify "otsu" must be 'auto' or 'fixed'/);

      if (!existsSync(LAB_A)) {
        t.diagnostic(`${LAB_A} is absent: the classification check on a real map is skipped`);
        return;
      }
      const counts = await page.evaluate(async () => {
        const { mount } = await import('./node_modules/ksmcmc/mount.js');
        const { Map: OccMap } = await import('./node_modules/ksmcmc/ksmcmc.js');
        const div = document.body.appendChild(document.createElement('div'));
        const widgetCounts = async (options) => {
          const w = await mount(div, options);
          const map = w.mapper.map;
          const c = map.counts();
          map.free();
          w.destroy();
          return c;
        };
        const bytes = new Uint8Array(await (await fetch('lab_a_scan.png')).arrayBuffer());
        const fixed = OccMap.fromBytes(bytes);
        const auto = fixed.reclassify('auto');
        const out = {
          url: await widgetCounts({ url: 'lab_a_scan.png' }),
          bytes: await widgetCounts({ map: bytes }),
          urlFixed: await widgetCounts({ url: 'lab_a_scan.png', classify: 'fixed' }),
          auto: auto.counts(),
          fixed: fixed.counts(),
        };
        fixed.free();
        auto.free();
        div.remove();
        return out;
      });
      assert.notDeepEqual(counts.auto, counts.fixed, 'the two rules differ on lab_a');
      assert.deepEqual(counts.url, counts.auto, 'mount({ url }) classifies auto');
      assert.deepEqual(counts.bytes, counts.auto, 'mount({ map: bytes }) classifies auto');
      assert.deepEqual(counts.urlFixed, counts.fixed, "classify: 'fixed'");
      assert.deepEqual(page.problems, []);
    } finally {
      await page.context().close();
    }
  });
});
