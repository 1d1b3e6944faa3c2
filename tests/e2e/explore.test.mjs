// The Exploration page (www/explore.html) in headless Chromium: a simulated robot explores a
// sample while the floor plan follows its growing map (Mapper.updateMap in the page's worker);
// the robot drives exactly as `ksmcmc explore` drives it, the page's main thread never runs a
// long task, and a bad upload shows a message. Also: a paint stroke on the live mapper hands
// the painted map to the running chain (updateMap) instead of starting it over.

import { after, before, describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { cli, done, openPage, REPO, snap, startBrowser, until } from './harness.mjs';

let env;
let tmp;
before(async () => {
  env = await startBrowser();
  tmp = mkdtempSync(join(tmpdir(), 'ksmcmc-explore-'));
});
after(async () => {
  await env?.close();
  if (tmp) rmSync(tmp, { recursive: true, force: true });
});

const SAMPLE = join(REPO, 'samples/office-small');

/** Starts recording the main thread's long tasks (over 50 ms) in `window.__long` (ms each). */
function watchLongTasks(page) {
  return page.evaluate(() => {
    window.__long = [];
    new PerformanceObserver((list) => {
      for (const e of list.getEntries()) window.__long.push(Math.round(e.duration));
    }).observe({ type: 'longtask' });
  });
}

/** What the map canvas shows: pixels by kind (the robot's orange, map gray, free white, other ink). */
function canvasKinds(page) {
  return page.evaluate(() => {
    const c = document.getElementById('map');
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    const n = { width: c.width, height: c.height, robot: 0, unknown: 0, free: 0, occupied: 0, world: 0 };
    for (let i = 0; i < d.length; i += 4) {
      const [r, g, b] = [d[i], d[i + 1], d[i + 2]];
      if (r === 232 && g === 89 && b === 12) n.robot++;
      else if (r === 160 && g === 160 && b === 160) n.unknown++;
      else if (r === 255 && g === 255 && b === 255) n.free++;
      else if (r === 0 && g === 0 && b === 0) n.occupied++;
      else if (Math.max(r, g, b) - Math.min(r, g, b) > 60) n.world++;
    }
    return n;
  });
}

async function openExplore(query = '') {
  const page = await openPage(env, `explore.html${query}`);
  await until(page, (s) => s.width > 0 && s.pathPoints >= 0 && s.generation >= 1);
  return page;
}

describe('Exploration page', () => {
  test('a sample: the robot drives, the chain follows with updates, the main thread never blocks', async () => {
    const page = await openExplore('?sample=office-small');
    const s0 = await snap(page);
    assert.equal(s0.sample, 'office-small');
    assert.equal(s0.travelledM, 0);
    assert.equal(s0.chain, false, 'no chain before the robot has driven');
    assert.ok(s0.seenFree > 0, 'the robot scanned where it stands');
    await watchLongTasks(page);
    await page.click('#run');
    await page.waitForFunction(() => document.documentElement.dataset.running === 'true');
    await until(page, (s) => s.updates >= 3 && s.iteration > 0, undefined, 60_000);
    // Running for a few seconds more while the long tasks are counted.
    await page.waitForTimeout(3000);
    const s1 = await snap(page);
    const long = await page.evaluate(() => window.__long);
    console.log(`explore: ${s1.travelledM.toFixed(1)} m, ${s1.updates} updates, ${s1.iteration} iterations, ${s1.frames} frames; long tasks ${JSON.stringify(long)}`);
    assert.ok(s1.travelledM > 10, `the robot drove: ${s1.travelledM} m`);
    assert.notDeepEqual(s1.robot, s0.robot, 'the robot moved');
    assert.ok(s1.seenFree > s0.seenFree, `cells seen grew: ${s0.seenFree} -> ${s1.seenFree}`);
    assert.ok(s1.pathPoints >= 2, 'the path has points');
    assert.ok(s1.units >= 1, `the floor plan has units: ${s1.units}`);
    assert.ok(s1.lastChanged > 0, `the last update changed cells: ${s1.lastChanged}`);
    const px = await canvasKinds(page);
    assert.ok(px.robot > 50, `the robot and its path are drawn: ${JSON.stringify(px)}`);
    // Part of the map is seen (free, walls, or the rooms' fills over them), part not yet.
    assert.ok(px.unknown > 1000 && px.occupied > 100 && px.free + px.world > 1000, `the robot's map is drawn, part seen, part not: ${JSON.stringify(px)}`);
    assert.ok(px.world > 200, `the floor plan is drawn over it: ${JSON.stringify(px)}`);
    // A loaded machine may show a few long tasks (garbage collection, compositing); none of
    // the page's own work is long: nothing near 200 ms, and at most a handful over 50 ms.
    assert.deepEqual(long.filter((ms) => ms > 200), [], 'no task of over 200 ms on the main thread');
    assert.ok(long.length <= 3, `at most 3 tasks of over 50 ms on the main thread: ${JSON.stringify(long)}`);
    // The figures shown are the numbers.
    assert.match(await page.textContent('#stat-updates'), /^\d+$/);
    assert.match(await page.textContent('#stat-seen'), /^\d+(\.\d)? % \([\d,]+\)$/);
    // Pause: the robot stops.
    await page.click('#run');
    await page.waitForFunction(() => document.documentElement.dataset.running === 'false');
    await page.waitForTimeout(300);
    const p1 = await snap(page);
    await page.waitForTimeout(500);
    const p2 = await snap(page);
    assert.equal(p2.travelledM, p1.travelledM, 'paused');
    assert.equal(p2.iteration, p1.iteration, 'the chain paused too');
    // Reset: the robot back at its start, no chain.
    await page.keyboard.press('r');
    await until(page, (s, g) => s.generation > g && s.travelledM === 0 && !s.chain && s.pathPoints <= 1, p2.generation);
    assert.deepEqual((await snap(page)).robot, s0.robot, 'the same seed, the same start');
    await done(page);
  });

  test('to the end: the robot drives as `ksmcmc explore` does, then the chain settles and the page stops', async () => {
    const out = join(tmp, 'cli');
    cli('explore', join(SAMPLE, 'map.yaml'), '--out', out, '--no-cold', '--iterations', '500', '--seed', '3');
    const report = JSON.parse(readFileSync(join(out, 'report.json'), 'utf8'));
    const page = await openExplore('?sample=office-small&seed=3&speed=64');
    await page.keyboard.press('Space');
    // The best world with its rooms while the robot drives (the worker loads the plan module
    // for it and keeps the plan until the chain's map or best world changes).
    await until(page, (s) => s.units > 0 && !s.finished, undefined, 60_000);
    const early = JSON.parse(await page.evaluate(() => window.__ksmcmc.bestWorldJson()));
    assert.ok(early.units.length > 0 && early.rooms.length > 0, `units ${early.units.length}, rooms ${early.rooms.length}`);
    await until(page, (s) => s.finished, undefined, 120_000);
    const f = await snap(page);
    // The robot is the library's: the same path, scans and map as natively, whatever the speed.
    assert.ok(Math.abs(f.travelledM - report.travelled_m) < 1e-9, `driven ${f.travelledM} m, natively ${report.travelled_m} m`);
    assert.equal(f.scans, report.scans);
    assert.equal(f.seenFree / f.truthFree, report.explored_free_share);
    assert.equal(f.updates, report.updates, 'as many updates as natively');
    assert.equal(f.pathPoints, report.scans, 'every scan is on the path');
    // The chain got the same maps at the same places: each update's metres, cells seen and
    // cells changed are the native timeline's.
    const native = JSON.parse(readFileSync(join(out, 'timeline.json'), 'utf8'));
    const timeline = await page.evaluate(() => window.__ksmcmc.timeline());
    assert.equal(timeline[0].update, 0, 'the chain started on the first map');
    assert.deepEqual(
      timeline.slice(1).map((r) => [r.update, r.travelledM, r.seenFree, r.changed]),
      native.map((r) => [r.update, r.travelled_m, r.seen_free, r.changed_cells]),
    );
    // The end of the exploration, as natively: the warm chain under the whole-map table and a
    // fresh chain each run the cold budget, and the one with the higher log posterior is kept.
    await until(page, (s) => s.renewal?.done, undefined, 240_000);
    const r = (await snap(page)).renewal;
    assert.equal(r.iterations, 100_000);
    assert.ok(r.warm.iteration - r.range.iteration >= r.iterations && r.fresh.iteration >= r.iterations, `both chains ran the budget: ${JSON.stringify(r)}`);
    assert.equal(r.adopted, r.fresh.logPosterior > r.warm.logPosterior, 'the higher log posterior is kept');
    // The CLI renews its last map too (there with five times its 500 iterations per update).
    assert.equal(report.renewal.iterations, 2500);
    await until(page, (s) => s.settled && !s.running, undefined, 180_000);
    const s = await snap(page);
    const keptK = r.adopted ? r.fresh.predictionRate : r.warm.predictionRate;
    assert.ok(s.k >= keptK - 1e-9, `the settled plan is the kept chain's, climbed on: K ${s.k} from ${keptK}`);
    assert.match(await page.textContent('#stat-phase'), /kept the (fresh|warm) chain/);
    assert.equal(await page.evaluate(() => document.documentElement.dataset.running), 'false');
    assert.ok(s.settledAt > 0);
    // The figures are drawn on the next frame after the worker's stop: wait for it (a loaded
    // machine delays frames).
    await page.waitForFunction(() => /settled at iteration/.test(document.querySelector('#stat-phase').textContent), null, { timeout: 10_000 });
    console.log(`explore to the end: ${s.updates} updates, K(W,M) ${s.k} at iteration ${s.iteration} (natively ${report.cell_prediction_rate} after ${report.updates} x ${report.iterations_per_update})`);
    assert.ok(s.k > 0.9, `the settled floor plan explains the robot's map: K(W,M) ${s.k}`);
    // Its world is a world.json the native tools read.
    const world = await page.evaluate(() => window.__ksmcmc.bestWorldJson());
    const worldPath = join(tmp, 'world.json');
    writeFileSync(worldPath, world);
    assert.equal(JSON.parse(world).units.length, s.units);
    // The native renderer loads it and checks it against the map.
    cli('render', join(SAMPLE, 'map.yaml'), '--world', worldPath, '--out', join(tmp, 'world.png'));
    await done(page);
  });

  test('a bad upload shows a message, and the page keeps working', async () => {
    const page = await openExplore();
    const before = await snap(page);
    const bad = join(tmp, 'broken.pgm');
    writeFileSync(bad, 'P5\n10 10\n255\nnot enough bytes');
    await page.setInputFiles('#file', bad);
    await page.waitForFunction(() => !document.getElementById('message').hidden);
    assert.match(await page.textContent('#message-text'), /\S/);
    assert.equal(await page.getAttribute('#message', 'role'), 'alert');
    const after = await snap(page);
    assert.equal(after.generation, before.generation, 'the sample stays loaded');
    // A map with no free cell: the robot has nowhere to stand.
    const walls = join(tmp, 'walls.pgm');
    writeFileSync(walls, Buffer.concat([Buffer.from('P5\n20 20\n255\n'), Buffer.alloc(400, 0)]));
    await page.setInputFiles('#file', walls);
    await page.waitForFunction(() => /free/.test(document.getElementById('message-text').textContent));
    // A bad setting says which.
    await page.fill('#update-every', '-3');
    await page.dispatchEvent('#update-every', 'change');
    await page.waitForFunction(() => /Update every/.test(document.getElementById('message-text').textContent));
    // And a good upload after them works.
    await page.setInputFiles('#file', [join(SAMPLE, 'map.yaml'), join(SAMPLE, 'map.pgm')]);
    await until(page, (s, g) => s.generation > g && s.name === 'map', before.generation);
    assert.equal((await snap(page)).width, 400);
    await done(page);
  });
});
