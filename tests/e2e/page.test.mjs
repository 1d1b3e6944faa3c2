// The Maps page (www/index.html) in headless Chromium: opening, generating and painting maps,
// checked against the native library through the CLI (target/debug/ksmcmc).

import { after, before, describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { existsSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import {
  DATASETS, canvasClasses, cli, done, download, nativeInfo, openPage, pgm, shownCounts, startBrowser,
} from './harness.mjs';

let env;
let tmp;
before(async () => {
  env = await startBrowser();
  tmp = mkdtempSync(join(tmpdir(), 'ksmcmc-e2e-'));
});
after(async () => {
  await env?.close();
  if (tmp) rmSync(tmp, { recursive: true, force: true });
});

/** The canvas shows the map one pixel per cell, in the classes the library counted. */
async function assertShows(page, expected) {
  const shown = await canvasClasses(page);
  assert.equal(shown.width, expected.width, 'canvas width = map width');
  assert.equal(shown.height, expected.height, 'canvas height = map height');
  assert.deepEqual(
    { free: shown.free, unknown: shown.unknown, occupied: shown.occupied },
    { free: expected.free, unknown: expected.unknown, occupied: expected.occupied },
    'canvas pixels by class = cells by class',
  );
  assert.deepEqual(await shownCounts(page), {
    free: expected.free, unknown: expected.unknown, occupied: expected.occupied,
  }, 'the counts on the page');
  assert.ok(shown.shown.width > 0 && shown.shown.height > 0, 'the canvas is visible');
  return shown;
}

/** Waits until painting has been drawn: the page redraws at most once per animation frame. */
function settled(page) {
  return page.evaluate(() => new Promise((ok) => requestAnimationFrame(() => requestAnimationFrame(ok))));
}

async function setFiles(page, files) {
  await page.setInputFiles('#file', files);
}

describe('Maps page', () => {
  test('starts with a generated map, drawn by the wasm renderer', async () => {
    const page = await openPage(env);
    assert.match(await page.textContent('#version'), /^\d+\.\d+\.\d+/);
    assert.match(await page.textContent('#map-name'), /seed 7/);
    const size = (await page.textContent('#size')).match(/(\d+) × (\d+)/);
    assert.ok(size, 'the size is shown');
    const counts = await shownCounts(page);
    await assertShows(page, { width: Number(size[1]), height: Number(size[2]), ...counts });
    assert.equal(counts.free + counts.unknown + counts.occupied, Number(size[1]) * Number(size[2]));
    assert.equal(await page.isVisible('#message'), false, 'no error is shown');
    await done(page);
  });

  test('opens a dataset map (PNG) and shows exactly its cells', async (t) => {
    const file = join(DATASETS, 'bormann2016/lab_ipa.png');
    if (!existsSync(file)) {
      t.skip(`${file} is not there (the repository is normally checked out beside shared/)`);
      return;
    }
    const page = await openPage(env);
    await setFiles(page, file);
    await page.waitForFunction(() => document.getElementById('map-name').textContent.includes('lab_ipa.png'));
    const native = nativeInfo(file);
    assert.ok(native.occupied > 1000 && native.free > 1000, 'the dataset map has walls and floor');
    const shown = await assertShows(page, native);
    // Scaled for display with nearest-neighbour pixels when enlarged, smoothly when shrunk.
    const rendering = await page.$eval('#map', (c) => getComputedStyle(c).imageRendering);
    assert.equal(rendering, shown.shown.width >= shown.width ? 'pixelated' : 'auto');
    assert.match(await page.textContent('#download-pgm'), /lab_ipa\.pgm/);
    await done(page);
  });

  test('opens a PGM, and a map.yaml with its image', async () => {
    // 6x4: a wall row, unknown (205) and free (254) cells.
    const samples = [
      0, 0, 0, 0, 0, 0,
      254, 254, 205, 205, 254, 254,
      254, 100, 205, 205, 254, 254,
      0, 0, 0, 0, 0, 254,
    ];
    const pgmPath = join(tmp, 'small.pgm');
    writeFileSync(pgmPath, pgm(6, 4, samples));
    // The YAML's own thresholds: with negate, white is occupied.
    const yamlPath = join(tmp, 'small.yaml');
    writeFileSync(yamlPath, 'image: small.pgm\nresolution: 0.1\norigin: [1.0, 2.0, 0.0]\nnegate: 1\noccupied_thresh: 0.65\nfree_thresh: 0.196\n');

    const page = await openPage(env);
    await setFiles(page, pgmPath);
    await page.waitForFunction(() => document.getElementById('map-name').textContent.includes('small.pgm'));
    await assertShows(page, nativeInfo(pgmPath));

    await setFiles(page, [yamlPath, pgmPath]);
    await page.waitForFunction(() => document.getElementById('status').textContent.includes('small.yaml'));
    const viaYaml = nativeInfo(yamlPath);
    assert.notDeepEqual(viaYaml, nativeInfo(pgmPath), 'the YAML changes the classes');
    await assertShows(page, viaYaml);

    // The YAML download keeps the loaded map's resolution and origin, and the pair loads back
    // natively to the same classes.
    const pgmOut = await download(page, '#download-pgm');
    const yamlOut = await download(page, '#download-yaml');
    assert.equal(pgmOut.name, 'small.pgm');
    assert.equal(yamlOut.name, 'small.yaml');
    const text = yamlOut.bytes.toString('utf8');
    assert.match(text, /resolution: 0\.1/);
    assert.match(text, /image: small\.pgm/);
    const back = mkdtempSync(join(tmp, 'back-'));
    writeFileSync(join(back, 'small.pgm'), pgmOut.bytes);
    writeFileSync(join(back, 'small.yaml'), yamlOut.bytes);
    assert.deepEqual(nativeInfo(join(back, 'small.yaml')), viaYaml);
    await done(page);
  });

  test('bad files and input show a message, and the page keeps working', async () => {
    const page = await openPage(env);
    const before = await canvasClasses(page);
    const alert = async () => {
      await page.waitForSelector('#message', { state: 'visible' });
      assert.equal(await page.getAttribute('#message', 'role'), 'alert');
      return page.textContent('#message-text');
    };

    await setFiles(page, { name: 'notes.png', mimeType: 'image/png', buffer: Buffer.from('hello, world') });
    assert.match(await alert(), /not an occupancy map/);
    assert.deepEqual(await canvasClasses(page), before, 'the old map is still shown');

    const truncated = readFileSync(join(tmp, 'small.pgm')).subarray(0, 20);
    await setFiles(page, { name: 'cut.pgm', mimeType: 'image/x-portable-graymap', buffer: truncated });
    assert.match(await alert(), /truncated PGM/);

    await setFiles(page, { name: 'map.yaml', mimeType: 'application/yaml', buffer: Buffer.from('image: lab.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n') });
    assert.match(await alert(), /names the image "lab\.pgm": select it together/);

    await setFiles(page, [
      { name: 'map.yaml', mimeType: 'application/yaml', buffer: Buffer.from('image: lab.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n') },
      { name: 'other.pgm', mimeType: 'image/x-portable-graymap', buffer: pgm(2, 2, [0, 0, 254, 254]) },
    ]);
    assert.match(await alert(), /names the image "lab\.pgm", but the selected image is "other\.pgm"/);

    await setFiles(page, [
      { name: 'map.yaml', mimeType: 'application/yaml', buffer: Buffer.from('image: lab.pgm\nresolution: fast\n') },
      { name: 'lab.pgm', mimeType: 'image/x-portable-graymap', buffer: pgm(2, 2, [0, 0, 254, 254]) },
    ]);
    assert.match(await alert(), /map\.yaml line 2/);

    await page.fill('#seed', '-3');
    await page.click('#generate');
    assert.match(await alert(), /not a whole number/);
    await page.fill('#seed', '7');
    await page.click('summary');
    await page.fill('#synth-config', '{"width": 0}');
    await page.click('#generate');
    assert.match(await alert(), /0x/);
    await page.fill('#synth-config', '');

    await page.fill('#blank-width', '0');
    await page.click('#blank-create');
    assert.match(await alert(), /Width must be a whole number/);
    assert.deepEqual(await canvasClasses(page), before, 'still the first map');

    // A good file clears the message.
    await setFiles(page, { name: 'good.pgm', mimeType: 'image/x-portable-graymap', buffer: pgm(3, 1, [0, 205, 254]) });
    await page.waitForSelector('#message', { state: 'hidden' });
    await assertShows(page, { width: 3, height: 1, free: 1, unknown: 1, occupied: 1 });
    await done(page);
  });

  test('painting with a pointer and with the keyboard changes the pixels', async () => {
    const page = await openPage(env);
    await page.fill('#blank-width', '40');
    await page.fill('#blank-height', '30');
    await page.selectOption('#blank-fill', '1');
    await page.click('#blank-create');
    await page.waitForFunction(() => document.getElementById('size').textContent.includes('40 × 30'));
    const blank = await assertShows(page, { width: 40, height: 30, free: 0, unknown: 1200, occupied: 0 });
    assert.ok(blank.shown.width >= 40 * 2, 'a small map is enlarged on screen');

    // A horizontal stroke with the default tool (occupied) and brush (3 cells).
    const box = await page.locator('#map').boundingBox();
    const y = box.y + box.height / 2;
    await page.mouse.move(box.x + box.width * 0.1, y);
    await page.mouse.down();
    await page.mouse.move(box.x + box.width * 0.9, y, { steps: 4 });
    await page.mouse.up();
    await settled(page);
    await page.waitForFunction(() => !document.getElementById('count-occupied').textContent.startsWith('0 '));
    const stroke = await canvasClasses(page);
    assert.ok(stroke.occupied >= 3 * 30, `a continuous 3-cell-wide line: ${stroke.occupied} cells`);
    await assertShows(page, { width: 40, height: 30, free: 0, unknown: 1200 - stroke.occupied, occupied: stroke.occupied });

    // Keyboard: tool 2 (free), move the cursor, hold Space while moving.
    await page.focus('#map');
    await page.keyboard.press('2');
    assert.equal(await page.isChecked('input[name="tool"][value="free"]'), true);
    // The cursor is where the pointer left it (right end of the stroke): go up and left.
    await page.keyboard.press('ArrowUp');
    await page.keyboard.press('Shift+ArrowUp');
    await page.keyboard.press('Shift+ArrowLeft');
    await page.keyboard.press('Shift+ArrowLeft');
    await page.keyboard.down(' ');
    for (let i = 0; i < 6; i++) await page.keyboard.press('ArrowRight');
    await page.keyboard.up(' ');
    await settled(page);
    await page.waitForFunction(() => !document.getElementById('count-free').textContent.startsWith('0 '));
    assert.match(await page.textContent('#cursor-pos'), /column \d+, row \d+/);
    const keyed = await shownCounts(page);
    assert.ok(keyed.free >= 7 * 3, `a free line of 7 brush stamps: ${keyed.free}`);
    assert.equal(keyed.occupied, stroke.occupied, 'away from the first stroke');
    await assertShows(page, { width: 40, height: 30, ...keyed });

    // Brush size keys, eraser (4) restores the loaded cells, Ctrl+Z undoes.
    await page.keyboard.press(']');
    assert.equal(await page.inputValue('#brush'), '4');
    await page.keyboard.press('[');
    await page.keyboard.press('Control+z');
    await settled(page);
    await page.waitForFunction(() => document.getElementById('count-free').textContent.startsWith('0 '));
    await assertShows(page, { width: 40, height: 30, free: 0, unknown: 1200 - stroke.occupied, occupied: stroke.occupied });
    await page.keyboard.press('4');
    await page.mouse.move(box.x + box.width * 0.05, y);
    await page.mouse.down();
    await page.mouse.move(box.x + box.width * 0.95, y, { steps: 4 });
    await page.mouse.up();
    await settled(page);
    await page.waitForFunction(() => document.getElementById('count-occupied').textContent.startsWith('0 '));
    await assertShows(page, { width: 40, height: 30, free: 0, unknown: 1200, occupied: 0 });

    // Paint, then download: the PGM loads natively with the same classes.
    await page.keyboard.press('1');
    await page.focus('#map');
    await page.keyboard.press('Enter');
    await settled(page);
    await page.waitForFunction(() => !document.getElementById('count-occupied').textContent.startsWith('0 '));
    const painted = await shownCounts(page);
    const out = await download(page, '#download-pgm');
    assert.equal(out.name, 'painted.pgm');
    const file = join(tmp, 'painted.pgm');
    writeFileSync(file, out.bytes);
    assert.deepEqual(nativeInfo(file), { width: 40, height: 30, ...painted });
    await done(page);
  });

  test('the canvas shows the same pixels as the native `ksmcmc render`', async () => {
    // A map with every gray level, so that every class and threshold is on it.
    const [w, h] = [97, 61];
    const samples = Array.from({ length: w * h }, (_, i) => (i * 7919) % 256);
    const map = join(tmp, 'grays.pgm');
    writeFileSync(map, pgm(w, h, samples));
    const png = join(tmp, 'grays.png');
    cli('render', map, '--out', png);

    const page = await openPage(env);
    await setFiles(page, map);
    await page.waitForFunction(() => document.getElementById('map-name').textContent.includes('grays.pgm'));
    const verdict = await page.evaluate(async (b64) => {
      const bytes = Uint8Array.from(atob(b64), (c) => c.charCodeAt(0));
      const bitmap = await createImageBitmap(new Blob([bytes], { type: 'image/png' }), {
        colorSpaceConversion: 'none',
        premultiplyAlpha: 'none',
      });
      const off = new OffscreenCanvas(bitmap.width, bitmap.height);
      const octx = off.getContext('2d');
      octx.drawImage(bitmap, 0, 0);
      const want = octx.getImageData(0, 0, bitmap.width, bitmap.height).data;
      const c = document.getElementById('map');
      const got = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
      if (want.length !== got.length) return `native ${bitmap.width}x${bitmap.height}, canvas ${c.width}x${c.height}`;
      let differ = 0;
      let first = -1;
      for (let i = 0; i < want.length; i++) {
        if (want[i] !== got[i]) {
          differ++;
          if (first < 0) first = i;
        }
      }
      return differ === 0 ? 'same' : `${differ} bytes differ, the first at pixel ${first >> 2}: native ${want.slice(first & ~3, (first & ~3) + 4)} canvas ${got.slice(first & ~3, (first & ~3) + 4)}`;
    }, readFileSync(png).toString('base64'));
    assert.equal(verdict, 'same');
    await done(page);
  });

  test('seed 7 gives the same files as the native `ksmcmc synth --seed 7`', async () => {
    const dir = join(tmp, 'synth-7');
    cli('synth', '--seed', '7', '--out', dir);
    const page = await openPage(env);
    await page.fill('#seed', '3');
    await page.click('#generate');
    await page.waitForFunction(() => document.getElementById('map-name').textContent.includes('seed 3'));
    await page.fill('#seed', '7');
    await page.click('#generate');
    await page.waitForFunction(() => document.getElementById('map-name').textContent.includes('seed 7'));
    const files = {
      'map.pgm': '#download-pgm',
      'map.yaml': '#download-yaml',
      'truth.json': '#download-truth',
      'truth_labels.pgm': '#download-labels',
    };
    for (const [name, button] of Object.entries(files)) {
      const got = await download(page, button);
      assert.equal(got.name, name);
      const want = readFileSync(join(dir, name));
      assert.ok(got.bytes.equals(want), `${name}: the browser's ${got.bytes.length} bytes differ from the native ${want.length}`);
    }
    await assertShows(page, nativeInfo(join(dir, 'map.yaml')));
    await done(page);
  });
});
