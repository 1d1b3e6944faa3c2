// The prior-shaping page (www/prior.html): the MLN prior reshapes a three-optimum posterior,
// weights edited by sliders change the posterior (numbers and canvas pixels), the Metropolis
// histogram fills in, and a syntax error is reported at its line and column.

import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import { openPage, startBrowser } from './harness.mjs';

let env;
before(async () => {
  env = await startBrowser();
});
after(async () => {
  await env?.close();
});

const snap = (page) => page.evaluate(() => window.__prior.snapshot());
const settled = (page) => page.evaluate(() => new Promise((ok) => requestAnimationFrame(() => requestAnimationFrame(ok))));
const canvasHash = (page) =>
  page.evaluate(() => {
    const c = document.getElementById('plot');
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    let red = 0;
    let h = 0;
    for (let i = 0; i < d.length; i += 4) {
      if (d[i] > 180 && d[i + 1] < 90 && d[i + 2] < 90) {
        red++;
        h = (h * 31 + i) % 1000000007;
      }
    }
    return { red, h };
  });

test('a slider weight reshapes the posterior and the MCMC histogram follows', async () => {
  const page = await openPage(env, 'prior.html');
  const s0 = await snap(page);
  assert.equal(s0.error, null);
  assert.deepEqual(s0.logWeights, [0, 0, 0]);
  // With a flat prior the three optima share the posterior.
  for (const m of s0.mass) assert.ok(m > 0.25 && m < 0.42, `mass ${s0.mass}`);
  const red0 = await canvasHash(page);
  assert.ok(red0.red > 100, 'the posterior curve is drawn');

  // Left weight to 3: the MLN prior favours the left region.
  await page.$eval('#w-Left', (el) => {
    el.value = '3';
    el.dispatchEvent(new Event('input', { bubbles: true }));
  });
  await settled(page);
  const s1 = await snap(page);
  assert.equal(s1.error, null);
  assert.ok(Math.abs(s1.logWeights[0] - 3) < 1e-9, `log weights ${s1.logWeights}`);
  assert.ok(s1.mass[0] > 0.85, `posterior mass ${s1.mass}`);
  assert.match(await page.inputValue('#kb'), /^3 Left\(x\)$/m, 'the slider edits the knowledge base');
  const red1 = await canvasHash(page);
  assert.notDeepEqual(red1, red0, 'the posterior curve moved');

  // The Metropolis histogram fills in and follows the posterior.
  await page.waitForFunction(() => window.__prior.snapshot().samples > 30000, null, { timeout: 30_000 });
  const s2 = await snap(page);
  assert.ok(Math.abs(s2.histMass[0] - s2.mass[0]) < 0.1, `histogram ${s2.histMass} vs posterior ${s2.mass}`);
  assert.deepEqual(page.problems, []);
  await page.context().close();
});

test('a syntax error is reported at its line and column and the last good prior stays', async () => {
  const page = await openPage(env, 'prior.html');
  const text = await page.inputValue('#kb');
  const lines = text.split('\n');
  const i = lines.findIndex((l) => l.startsWith('0 Middle(x)'));
  lines[i] = '0 Middle(x) ^';
  await page.fill('#kb', lines.join('\n'));
  await settled(page);
  const s = await snap(page);
  assert.ok(s.error, 'an error is reported');
  assert.equal(s.error.line, i + 1);
  assert.ok(s.error.column >= 13, `column ${s.error.column}`);
  assert.equal(s.goodKb, text, 'the last good knowledge base stays');
  assert.match(await page.textContent('#kb-error'), new RegExp(`^line ${i + 1}, column ${s.error.column}:`));
  assert.equal(await page.textContent('#gutter .bad'), `${i + 1}\n`);
  assert.deepEqual(s.logWeights, [0, 0, 0]);
  // Fixing it clears the error.
  await page.fill('#kb', text.replace('0 Middle(x)', '2 Middle(x)'));
  await settled(page);
  const fixed = await snap(page);
  assert.equal(fixed.error, null);
  assert.ok(fixed.mass[1] > 0.7, `mass ${fixed.mass}`);
  assert.equal(await page.$('#gutter .bad'), null);
  assert.deepEqual(page.problems, []);
  await page.context().close();
});
