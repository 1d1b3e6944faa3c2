// The table-top page (www/tabletop.html) in headless Chromium: a generated scene is analysed
// in animation frames, the probability table and both canvases fill, the decisions agree with
// the generator's truth, the rules editor reports syntax errors at their line, and a bad
// scene upload shows a message while the page keeps working.

import { after, before, describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { done, download, openPage, snap, startBrowser } from './harness.mjs';

let env;
let tmp;
before(async () => {
  env = await startBrowser();
  tmp = mkdtempSync(join(tmpdir(), 'ksmcmc-tabletop-'));
});
after(async () => {
  await env?.close();
  if (tmp) rmSync(tmp, { recursive: true, force: true });
});

/** Pixels of a canvas that are not the background (245, 245, 245) nor transparent. */
function inked(page, selector) {
  return page.evaluate((sel) => {
    const c = document.querySelector(sel);
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    let n = 0;
    for (let i = 0; i < d.length; i += 4) {
      if (d[i + 3] > 0 && !(d[i] === 245 && d[i + 1] === 245 && d[i + 2] === 245)) n++;
    }
    return { width: c.width, height: c.height, inked: n };
  }, selector);
}

/** The table's rows as text cells. */
const tableRows = (page) =>
  page.$$eval('#probs tbody tr', (rows) => rows.map((r) => [...r.cells].map((c) => c.textContent)));

describe('table-top page', () => {
  test('a generated scene is analysed live and agrees with its truth', async () => {
    const page = await openPage(env, 'tabletop.html');
    await page.fill('#synth-seed', '5');
    await page.fill('#synth-objects', '8');
    await page.click('#generate');
    await page.click('#run');
    await page.waitForTimeout(1000);
    await page.click('#run');
    const s = await snap(page);
    assert.equal(s.running, false);
    assert.ok(s.iteration > 0, `the chain ran: ${s.iteration}`);
    assert.ok(s.objects >= 3 && s.objects <= 8, `objects: ${s.objects}`);
    // Objects on the table are the true estimates and those hidden under them (seed 5: all 8
    // placed); false estimates are not objects. The page says so.
    const scene = JSON.parse(await page.evaluate(() => window.__ksmcmc.sceneText()));
    const hidden = scene.hidden_objects?.length ?? 0;
    const falses = scene.objects.filter((o) => o.truth.false).length;
    assert.equal(s.objects - falses + hidden, 8, 'seen + hidden = the objects asked for');
    assert.equal(
      await page.textContent('#scene-name'),
      `synthetic, seed 5 (8 objects: ${s.objects - falses} seen, ${hidden} hidden under them; ${s.objects} estimates, ${falses} false)`,
    );
    assert.equal(s.error, null);
    const rows = await tableRows(page);
    assert.equal(rows.length, s.objects, 'one row per object');
    for (const r of rows) {
      for (const p of r.slice(1, 5).map(Number)) assert.ok(p >= 0 && p <= 1, `probability ${p} in [0, 1]: ${r}`);
      for (const d of r.slice(5, 7)) assert.ok(['true', 'false', 'undecided'].includes(d), `decision ${d}`);
    }
    const view = await inked(page, '#view');
    const graph = await inked(page, '#graph');
    assert.ok(view.width > 100 && view.inked > view.width * view.height * 0.05, `view drawn: ${JSON.stringify(view)}`);
    assert.ok(graph.width > 50 && graph.inked > 500, `graph drawn: ${JSON.stringify(graph)}`);
    // Decisions against the generator's truth: most objects agree on both queries.
    const objs = s.analysis.objects;
    assert.ok(objs.every((o) => o.truth), 'the generated scene has truth');
    const agree = objs.filter(
      (o) => (o.hidden === 'true') === o.truth.hidden && (o['false'] === 'true') === o.truth['false'],
    ).length;
    assert.ok(agree >= Math.ceil(objs.length * 0.6), `${agree} of ${objs.length} objects agree with the truth`);
    // The scene downloads as the JSON the page analyses.
    const saved = await download(page, '#download');
    assert.equal(saved.name, 'scene.json');
    assert.equal(JSON.parse(saved.bytes.toString('utf8')).objects.length, s.objects);
    // The time of a whole analysis of an 8-object scene, 100 iterations.
    const times = [];
    let benchObjects = 0;
    for (let i = 0; i < 5; i++) {
      const b = await page.evaluate(() => window.__ksmcmc.bench(8, 100, 3));
      times.push(b.ms);
      benchObjects = b.objects;
    }
    times.sort((a, b) => a - b);
    console.log(`# whole analysis, ${benchObjects} objects, 100 iterations: median ${times[2].toFixed(1)} ms (${times.map((t) => t.toFixed(1)).join(', ')})`);
    await done(page);
  });

  test('the rules editor reports syntax errors at their line and keeps the last good rules', async () => {
    const page = await openPage(env, 'tabletop.html');
    const before = await snap(page);
    assert.match(before.rulesError, /parse/);
    const good = await page.inputValue('#rules');
    assert.ok(good.length > 100, 'the built-in rules are in the editor');
    const lines = good.split('\n');
    const at = lines.length + 2; // appended after one blank line
    await page.fill('#rules', `${good}${good.endsWith('\n') ? '' : '\n'}\n0.5 stable(x) ^ ^ hidden(x)\n`);
    await page.waitForFunction(() => /line \d+/.test(document.getElementById('rules-error').textContent));
    const msg = await page.textContent('#rules-error');
    const line = Number(/line (\d+)/.exec(msg)[1]);
    assert.equal(line, good.endsWith('\n') ? at - 1 : at, `the error is on the appended line: ${msg}`);
    let s = await snap(page);
    // The same editor as the floor-plan rules page: the line marked, the token underlined.
    assert.equal(s.rulesBadLine, line);
    assert.equal(await page.textContent('#rules-gutter .bad'), `${line}\n`);
    const column = Number(/column (\d+)/.exec(msg)[1]);
    const expected = '0.5 stable(x) ^ ^ hidden(x)'.slice(column - 1).match(/^([A-Za-z0-9_.]+|[=<>]+|.)/)?.[0] ?? '\u00a0';
    assert.equal(s.rulesUnderlined, expected, `underline at column ${column}`);
    await page.click('#rules-apply');
    s = await snap(page);
    assert.ok(s.error, 'applying broken rules shows a message');
    assert.equal(s.rulesInUse, good, 'the last good rules stay in use');
    // The page still works with the good rules, and an edit that parses applies.
    const edited = `${good}\n0.5 hover(o1) => hidden(o1)\n`;
    await page.fill('#rules', edited);
    await page.click('#rules-apply');
    s = await snap(page);
    assert.equal(s.error, null);
    assert.equal(s.rulesInUse, edited, 'edited rules apply without reloading');
    await page.click('#step');
    s = await snap(page);
    assert.ok(s.iteration >= 100);
    assert.equal(s.rows, s.objects);
    await done(page);
  });

  test('a bad scene upload shows a message and the page keeps working', async () => {
    const page = await openPage(env, 'tabletop.html');
    const first = await snap(page);
    const bad = join(tmp, 'bad-scene.json');
    writeFileSync(bad, JSON.stringify({ table: { size: [1, 0.6] }, objekts: [] }));
    await page.setInputFiles('#file', bad);
    await page.waitForSelector('#message:not([hidden])');
    const text = await page.textContent('#message-text');
    assert.match(text, /objekts|objects/, text);
    const s = await snap(page);
    assert.equal(s.objects, first.objects, 'the old scene stays');
    await page.click('#step');
    assert.ok((await snap(page)).iteration >= 100, 'the chain still steps');
    // A good upload after the bad one works.
    const scene = await page.evaluate(() => window.__ksmcmc.synthText?.() ?? null);
    if (scene) {
      const goodPath = join(tmp, 'scene.json');
      writeFileSync(goodPath, scene);
      await page.setInputFiles('#file', goodPath);
      await page.waitForSelector('#message', { state: 'hidden' });
      assert.equal((await snap(page)).error, null);
    }
    await done(page);
  });
});
