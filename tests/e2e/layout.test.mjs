// Every page is readable on a phone: at a 390 px wide viewport nothing makes the page wider
// than the screen (no sideways scrolling), once the page has built its content.

import { after, before, describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { openPage, startBrowser } from './harness.mjs';

let env;
before(async () => {
  env = await startBrowser();
});
after(async () => {
  await env?.close();
});

const PAGES = ['index.html', 'mapper.html', 'explore.html', 'embed.html', 'rules.html', 'rules.html?sample=partial', 'prior.html', 'tabletop.html'];
/** What a page must have built before it is measured, where its widest content comes late. */
const BUILT = { 'rules.html?sample=partial': 'window.__rules?.snapshot().placeholderRows > 0' };

describe('Phone widths', () => {
  for (const path of PAGES) {
    test(`${path} fits a 390 px wide screen`, async () => {
      const page = await openPage(env, path, { width: 390, height: 844 });
      // Let the page's frame loops lay out what they draw.
      await page.waitForTimeout(500);
      if (BUILT[path]) await page.waitForFunction(BUILT[path], null, { timeout: 60_000 });
      const { width, culprits } = await page.evaluate(() => {
        const limit = document.documentElement.clientWidth;
        const culprits = [...document.querySelectorAll('body *')]
          .filter((e) => e.getBoundingClientRect().right > limit + 0.5 && getComputedStyle(e).position !== 'fixed')
          .filter((e) => !e.closest('.skip'))
          .slice(0, 8)
          .map((e) => `${e.tagName.toLowerCase()}${e.id ? `#${e.id}` : ''}${e.className && typeof e.className === 'string' ? `.${e.className.trim().split(/\s+/).join('.')}` : ''} (right ${Math.round(e.getBoundingClientRect().right)})`);
        return { width: document.documentElement.scrollWidth, culprits };
      });
      assert.ok(width <= 390, `${path} is ${width} px wide at a 390 px viewport; too wide: ${culprits.join(', ')}`);
      // Nor does a table scroll sideways inside its box (issue 33).
      const sideways = await page.$$eval('.table-scroll', (boxes) =>
        boxes.filter((b) => b.offsetParent !== null && b.scrollWidth > b.clientWidth + 1).map((b) => `${b.firstElementChild?.id || b.className}: ${b.scrollWidth} in ${b.clientWidth}`));
      assert.deepEqual(sideways, [], `${path}: tables wider than their box`);
      await page.context().close();
    });
  }
});
