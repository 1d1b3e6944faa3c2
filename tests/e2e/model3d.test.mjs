// The 3D world: `world.glb` from `ksmcmc floorplan` on a generated floor and on a sample map,
// and from the live mapper's worker, passes the Khronos glTF validator with no errors; the
// mapper's 3D view loads three.js only when opened and renders the best world with WebGL in
// headless Chromium (SwiftShader), with no console errors.

import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { validateBytes } from 'gltf-validator';
import { REPO, cli, openPage, startBrowser } from './harness.mjs';

let env;
let tmp;
before(async () => {
  env = await startBrowser();
  tmp = mkdtempSync(join(tmpdir(), 'ksmcmc-3d-'));
});
after(async () => {
  await env?.close();
  if (tmp) rmSync(tmp, { recursive: true, force: true });
});

/** The validator's report of a .glb, failing with its messages if it finds errors. */
async function valid(bytes, what) {
  const report = await validateBytes(new Uint8Array(bytes));
  const errors = report.issues.messages.filter((m) => m.severity === 0);
  assert.equal(report.issues.numErrors, 0, `${what}: ${JSON.stringify(errors.slice(0, 5))}`);
  assert.equal(report.info.version, '2.0');
  return report;
}

test('world.glb of a generated floor and of a sample map validates with no errors', async () => {
  cli('synth', '--seed', '5', '--out', join(tmp, 'synth'));
  const maps = [
    ['generated floor', join(tmp, 'synth/map.yaml')],
    ['office-rotated sample', join(REPO, 'samples/office-rotated/map.yaml')],
  ];
  for (const [what, map] of maps) {
    const out = join(tmp, what.replace(/\W+/g, '-'));
    cli('floorplan', map, '--out', out, '--iterations', '4000', '--wall-height', '2.7', '--door-height', '2.1');
    const report = await valid(readFileSync(join(out, 'world.glb')), what);
    assert.ok(report.info.totalTriangleCount > 100, `${what}: ${report.info.totalTriangleCount} triangles`);
    assert.equal(report.issues.numWarnings, 0, `${what}: ${JSON.stringify(report.issues.messages)}`);
  }
});

test('the 3D view loads three.js when opened and renders the best world', async () => {
  const page = await openPage(env, 'mapper.html?sample=office-small&ipf=3000&seed=2');
  const three = [];
  page.on('request', (r) => {
    if (r.url().includes('/vendor/three/')) three.push(r.url());
  });
  await page.click('#step');
  await page.evaluate(() => window.__ksmcmc.idle());
  assert.deepEqual(three, [], 'three.js is not loaded before the 3D view opens');

  // The worker's world.glb validates too.
  const glb = await page.evaluate(async () => Array.from(await window.__ksmcmc.mapper.worldGlb()));
  await valid(Uint8Array.from(glb), 'the mapper\'s worldGlb');

  // Key 3 opens the view (the focus on the page, not in a field).
  await page.locator('body').press('3');
  await page.waitForFunction(() => document.getElementById('view3d-panel').dataset.state === 'ready', null, { timeout: 60_000 });
  assert.ok(three.some((u) => u.endsWith('three.module.js')), `three.js loaded: ${three}`);
  assert.equal(await page.getAttribute('#view-3d', 'aria-pressed'), 'true');
  const v = await page.evaluate(() => window.__ksmcmc.view3d());
  assert.equal(v.error, null);
  assert.ok(v.nodes.includes('walls'), `nodes: ${v.nodes}`);
  assert.ok(v.nodes.some((n) => n.startsWith('room')), `nodes: ${v.nodes}`);

  // A WebGL canvas whose picture is not blank: most pixels differ from the background, in many
  // colours (walls, floors of several types, shading).
  const picture = await page.evaluate(async () => {
    const c = document.getElementById('view3d');
    const gl = c.getContext('webgl2') ?? c.getContext('webgl');
    const img = new Image();
    img.src = c.toDataURL('image/png');
    await img.decode();
    const copy = new OffscreenCanvas(img.width, img.height);
    const ctx = copy.getContext('2d');
    ctx.drawImage(img, 0, 0);
    const d = ctx.getImageData(0, 0, img.width, img.height).data;
    const [br, bg, bb] = [d[0], d[1], d[2]]; // a corner: the background
    let drawn = 0;
    const colours = new Set();
    for (let i = 0; i < d.length; i += 4) {
      if (Math.abs(d[i] - br) + Math.abs(d[i + 1] - bg) + Math.abs(d[i + 2] - bb) > 30) drawn++;
      colours.add((d[i] >> 3) * 1024 + (d[i + 1] >> 3) * 32 + (d[i + 2] >> 3));
    }
    return { webgl: Boolean(gl), width: c.width, height: c.height, drawn, pixels: d.length / 4, colours: colours.size };
  });
  assert.ok(picture.webgl, 'a WebGL context');
  assert.ok(picture.width > 100 && picture.height > 100, JSON.stringify(picture));
  assert.ok(picture.drawn > picture.pixels * 0.2, `the model covers the picture: ${JSON.stringify(picture)}`);
  assert.ok(picture.colours > 20, `shaded in many colours: ${JSON.stringify(picture)}`);

  // Keyboard: + zooms in (the picture changes), and heights out of range are said, not thrown.
  const before = await page.evaluate(() => document.getElementById('view3d').toDataURL());
  await page.focus('#view3d');
  await page.keyboard.press('+');
  assert.notEqual(await page.evaluate(() => document.getElementById('view3d').toDataURL()), before);
  await page.fill('#door-height', '9');
  await page.press('#door-height', 'Enter');
  await page.waitForFunction(() => window.__ksmcmc.view3d().error);
  assert.match(await page.textContent('#view3d-status'), /No 3D world: door height 9 m/);

  const problems = page.problems;
  await page.context().close();
  assert.deepEqual(problems, [], 'the page logged errors');
});
