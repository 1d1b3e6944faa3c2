// The landing page opens on a plan and leads to the live mapper on a sample, and the pictures
// in docs/ come from here: the test lets the landing page's lead explain office-small, follows
// its link, lets the chain run, checks that the plan is drawn (walls, room tints, room labels,
// the legend beside the map), checks that on a phone the map comes first, and, only with
// UPDATE_SCREENSHOT=1, writes docs/landing.png, docs/screenshot.png and
// docs/screenshot-phone.png. Without the variable the committed pictures are left alone, so
// running the tests never dirties the checkout.
//
//   make www-pkg cli
//   cd tests/e2e && UPDATE_SCREENSHOT=1 CHROMIUM=/usr/bin/chromium node --test screenshot.test.mjs

import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdirSync, statSync } from 'node:fs';
import { join } from 'node:path';
import { REPO, openPage, startBrowser } from './harness.mjs';

let env;
before(async () => {
  env = await startBrowser();
});
after(async () => {
  await env?.close();
});

/** Pixels of the map canvas by kind: wall blue, room-orange tint, label text red. */
function kinds(page) {
  return page.evaluate(() => {
    const c = document.getElementById('map');
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    const n = { width: c.width, height: c.height, wall: 0, tint: 0, text: 0 };
    for (let i = 0; i < d.length; i += 4) {
      const [r, g, b] = [d[i], d[i + 1], d[i + 2]];
      if (r === 0 && g === 0 && b === 255) n.wall++;
      if (r === 247 && g === 222 && b === 166) n.tint++; // room_fill_rgb(Room)
      if (r === 150 && g === 0 && b === 0) n.text++; // LABEL_TEXT_RGBA
    }
    return n;
  });
}

/** Writes a picture of `locator` (or the page) to docs/NAME with UPDATE_SCREENSHOT=1, under `kb` kB. */
async function picture(page, name, locator, kb = 150) {
  if (process.env.UPDATE_SCREENSHOT !== '1') return;
  const out = join(REPO, 'docs', name);
  mkdirSync(join(REPO, 'docs'), { recursive: true });
  await (locator ?? page).screenshot({ path: out, animations: 'disabled' });
  const size = statSync(out).size;
  assert.ok(size < kb * 1000, `docs/${name} is ${size} bytes; keep it under ${kb} kB`);
}

test('the Maps page opens on a plan and leads to the live mapper on a sample, which draws a readable plan', async () => {
  const page = await openPage(env, 'index.html', { width: 1200, height: 760 });
  // The lead explains the office sample as the page opens, and stops once it has settled.
  await page.waitForFunction(() => window.__lead?.stats().settledAt !== null && !window.__lead.running, null, { timeout: 120_000 });
  const plan = await page.evaluate(() => {
    const c = document.querySelector('#lead-plan canvas');
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    const n = { wall: 0, tint: 0 };
    for (let i = 0; i < d.length; i += 4) {
      if (d[i] === 0 && d[i + 1] === 0 && d[i + 2] === 255) n.wall++;
      if (d[i] === 247 && d[i + 1] === 222 && d[i + 2] === 166) n.tint++;
    }
    return { ...n, units: window.__lead.stats().bestUnits, top: c.getBoundingClientRect().top };
  });
  assert.ok(plan.units >= 4 && plan.wall > 500 && plan.tint > 2000, `the lead shows a plan: ${JSON.stringify(plan)}`);
  assert.ok(plan.top < 760, `the plan is on the first screen: top ${plan.top}`);
  await picture(page, 'landing.png', page.locator('.lead'));
  const lead = page.locator('#lead-mapper');
  assert.ok(await lead.isVisible(), 'the lead link is shown');
  const box = await lead.boundingBox();
  assert.ok(box.y < 300, `the lead is at the top of the page: y = ${box.y}`);
  await Promise.all([page.waitForURL(/mapper\.html\?sample=office-small&autoplay=1/), lead.click()]);
  await page.waitForFunction(() => document.documentElement.dataset.state === 'ready', null, { timeout: 60_000 });
  await page.waitForFunction(() => window.__ksmcmc?.snapshot().iteration >= 4000, null, { timeout: 60_000 });
  // Pause (the Start/Pause button), so that the checks and the picture are of one state.
  await page.click('#run');
  await page.evaluate(() => window.__ksmcmc.idle());
  const s = await page.evaluate(() => window.__ksmcmc.snapshot());
  assert.equal(s.sample, 'office-small');
  assert.ok(s.bestUnits >= 4, `units found: ${s.bestUnits}`);
  const n = await kinds(page);
  assert.ok(n.wall > 500, `walls drawn: ${JSON.stringify(n)}`);
  assert.ok(n.tint > 2000, `rooms tinted: ${JSON.stringify(n)}`);
  assert.ok(n.text > 50, `labels drawn: ${JSON.stringify(n)}`);
  const legend = await page.$$eval('#map-legend span', (spans) => spans.map((s) => s.dataset.name));
  assert.ok(legend.includes('room') && legend.includes('door'), `the legend beside the map: ${legend}`);
  assert.deepEqual(page.problems, [], 'the page logged errors');
  await picture(page, 'screenshot.png', page.locator('.mapper-grid'));
  await page.context().close();
});

test('the live mapper on a phone: the map comes first', async () => {
  const page = await openPage(env, 'mapper.html?sample=office-small&autoplay=1', { width: 390, height: 844 });
  await page.waitForFunction(() => window.__ksmcmc?.snapshot().iteration >= 4000, null, { timeout: 60_000 });
  await page.click('#run');
  await page.evaluate(() => window.__ksmcmc.idle());
  const box = await page.locator('#map').boundingBox();
  assert.ok(box.y < 844 && box.y + box.height / 2 < 844, `the map is on the first screen: ${JSON.stringify(box)}`);
  const controls = await page.locator('.controls').boundingBox();
  assert.ok(controls.y > box.y, 'the controls come after the map');
  assert.deepEqual(page.problems, [], 'the page logged errors');
  await picture(page, 'screenshot-phone.png');
  await page.context().close();
});
