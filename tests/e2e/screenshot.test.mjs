// The landing page leads to the live mapper on a sample, and the README's picture comes from
// here: the test follows the Maps page's lead link, lets the chain run on office-small, checks
// that the plan is drawn (walls, room tints, labels, a legend) and, only with
// UPDATE_SCREENSHOT=1, writes the picture to docs/screenshot.png. Without the variable the
// committed picture is left alone, so running the tests never dirties the checkout.
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

test('the Maps page leads to the live mapper on a sample, which draws a readable plan', async () => {
  const page = await openPage(env, 'index.html', { width: 1200, height: 760 });
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
  assert.deepEqual(page.problems, [], 'the page logged errors');

  if (process.env.UPDATE_SCREENSHOT === '1') {
    const out = join(REPO, 'docs/screenshot.png');
    mkdirSync(join(REPO, 'docs'), { recursive: true });
    const grid = page.locator('.mapper-grid');
    await grid.screenshot({ path: out, animations: 'disabled' });
    const size = statSync(out).size;
    assert.ok(size < 150_000, `docs/screenshot.png is ${size} bytes; keep it under 150 kB`);
  }
  await page.context().close();
});
