// Route mode of the live mapper in headless Chromium: G enters it, two clicks on the map pick
// the start and the goal, the path is drawn over the map and its rooms and doors listed, the
// route is the one the native `ksmcmc route` plans on the exported world and labels, typed
// ends that are no free cells say why, and Esc leaves the mode.

import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { REPO, cli, openPage, readPgm16, startBrowser } from './harness.mjs';

let env;
let tmp;
before(async () => {
  env = await startBrowser();
  tmp = mkdtempSync(join(tmpdir(), 'ksmcmc-route-'));
});
after(async () => {
  await env?.close();
  if (tmp) rmSync(tmp, { recursive: true, force: true });
});

/** A cell in the middle (in scan order) of each of the two largest rooms of `labels`. */
function twoRooms({ width, values }) {
  const cells = new Map();
  values.forEach((l, i) => {
    if (l) (cells.get(l) ?? cells.set(l, []).get(l)).push(i);
  });
  const big = [...cells.values()].sort((a, b) => b.length - a.length).slice(0, 2);
  assert.equal(big.length, 2, 'the best world has two rooms');
  return big.map((c) => [c[c.length >> 1] % width, Math.floor(c[c.length >> 1] / width)]);
}

const route = (page) => page.evaluate(() => window.__ksmcmc.route());

test('route mode: click start and goal, see the path and its doors, as ksmcmc route plans it', async () => {
  const page = await openPage(env, 'mapper.html?sample=office-small&ipf=3000&seed=2');
  await page.click('#step');
  await page.evaluate(() => window.__ksmcmc.idle());
  const pgm = new Uint8Array(await page.evaluate(async () => Array.from(await window.__ksmcmc.mapper.labelsPgm())));
  const labels = readPgm16(pgm);
  const [a, b] = twoRooms(labels);

  // G enters route mode (the key, with the focus on the page).
  await page.locator('body').press('g');
  assert.equal(await page.getAttribute('#route-mode', 'aria-pressed'), 'true');
  assert.equal((await route(page)).active, true);

  const box = await page.locator('#map').boundingBox();
  const click = ([x, y]) =>
    page.mouse.click(box.x + ((x + 0.5) * box.width) / labels.width, box.y + ((y + 0.5) * box.height) / labels.height);
  await click(a);
  assert.deepEqual((await route(page)).from, a);
  await click(b);
  await page.waitForFunction(() => {
    const r = window.__ksmcmc.route();
    return r.result || r.error;
  });
  const r = await route(page);
  assert.equal(r.error, null);
  assert.deepEqual(r.to, b);
  assert.deepEqual(r.result.path[0], a);
  assert.deepEqual(r.result.path.at(-1), b);
  assert.ok(r.result.rooms.length >= 2, `two rooms at least: ${r.result.rooms}`);

  // The page lists the rooms and doors, and the layer over the map shows the path.
  assert.equal(await page.locator('#route-rooms li').count(), r.result.rooms.length);
  assert.equal(await page.getAttribute('#route-doors', 'data-doors'), r.result.doors.join(','));
  assert.match(await page.textContent('#route-summary'), / m from .* through \d+ rooms? and \d+ doors?\./);
  const inked = await page.evaluate(() => {
    const c = document.getElementById('route-layer');
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    let n = 0;
    for (let i = 3; i < d.length; i += 4) n += d[i] > 0;
    return n;
  });
  assert.ok(inked > r.result.path.length, `the path is drawn (${inked} pixels)`);

  // The same route as the native CLI plans on the exported world and labels.
  const world = await page.evaluate(() => window.__ksmcmc.mapper.bestWorldJson());
  writeFileSync(join(tmp, 'world.json'), world);
  writeFileSync(join(tmp, 'labels.pgm'), pgm);
  const sample = join(REPO, 'samples/office-small/map.yaml');
  const native = JSON.parse(
    cli('route', sample, join(tmp, 'world.json'), '--labels', join(tmp, 'labels.pgm'), '--from', a.join(','), '--to', b.join(',')),
  );
  assert.deepEqual(r.result, native);

  // Typed ends: an unknown cell is no start, and the page says so without an alert.
  await page.fill('#route-from', '0,0');
  await page.fill('#route-to', b.join(','));
  await page.click('#route-plan');
  await page.waitForFunction(() => window.__ksmcmc.route().error);
  assert.match(await page.textContent('#route-summary'), /No route: the start \(0, 0\) is an unknown cell/);
  assert.equal(await page.isHidden('#message'), true);

  // Esc leaves route mode; clicks then pick nothing.
  await page.keyboard.press('Escape');
  assert.equal(await page.getAttribute('#route-mode', 'aria-pressed'), 'false');
  await click(a);
  assert.deepEqual((await route(page)).from, [0, 0]);

  const problems = page.problems;
  await page.context().close();
  assert.deepEqual(problems, [], 'the page logged errors');
});

test('route mode: a placeholder as the goal, listed most likely first, as ksmcmc route --to-placeholder plans it', async () => {
  const page = await openPage(env, 'mapper.html?sample=partial&ipf=3000&seed=2');
  await page.click('#step');
  await page.evaluate(() => window.__ksmcmc.idle());
  const pgm = new Uint8Array(await page.evaluate(async () => Array.from(await window.__ksmcmc.mapper.labelsPgm())));
  const labels = readPgm16(pgm);
  const [a] = twoRooms(labels);
  const world = JSON.parse(await page.evaluate(() => window.__ksmcmc.mapper.bestWorldJson()));
  assert.ok(world.placeholders?.length > 0, 'the partly explored sample has frontiers');

  await page.locator('body').press('g');
  await page.waitForFunction(() => window.__ksmcmc.route().placeholders.length > 0);
  // The select lists the best world's placeholders, the likeliest new room first.
  const options = await page.$$eval('#route-placeholder option', (os) => os.map((o) => o.value).filter(Boolean));
  const byP = [...world.placeholders].sort((p, q) => q.p_new_room - p.p_new_room || p.id - q.id).map((p) => String(p.id));
  assert.deepEqual(options, byP);
  assert.equal(await page.isDisabled('#route-placeholder'), false);

  const box = await page.locator('#map').boundingBox();
  await page.mouse.click(box.x + ((a[0] + 0.5) * box.width) / labels.width, box.y + ((a[1] + 0.5) * box.height) / labels.height);
  const id = options[0];
  await page.selectOption('#route-placeholder', id);
  await page.waitForFunction(() => {
    const r = window.__ksmcmc.route();
    return r.result || r.error;
  });
  const r = await route(page);
  const p = world.placeholders.find((q) => String(q.id) === id);
  assert.equal(r.error, null);
  assert.deepEqual(r.to, [p.x, p.y]);
  assert.equal(await page.inputValue('#route-to'), `${p.x},${p.y}`);
  assert.deepEqual(r.result.path.at(-1), [p.x, p.y]);

  writeFileSync(join(tmp, 'world-p.json'), JSON.stringify(world));
  writeFileSync(join(tmp, 'labels-p.pgm'), pgm);
  const sample = join(REPO, 'samples/partial/map.yaml');
  const native = JSON.parse(
    cli('route', sample, join(tmp, 'world-p.json'), '--labels', join(tmp, 'labels-p.pgm'), '--from', a.join(','), '--to-placeholder', id),
  );
  assert.deepEqual(r.result, native);

  const problems = page.problems;
  await page.context().close();
  assert.deepEqual(problems, [], 'the page logged errors');
});
