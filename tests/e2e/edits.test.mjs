// The mapper page's room edits (issue 15): select a room on the map or in the Rooms table,
// retype, name, merge and split it; the chain goes on with the edits as hard evidence; undo,
// export, import and Reset keep the list the worker holds (`editsJson`) and the page shows.

import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import { download, openPage, snap, startBrowser } from './harness.mjs';

let env;
before(async () => {
  env = await startBrowser();
});
after(async () => {
  await env?.close();
});

const idle = (page) => page.evaluate(() => window.__ksmcmc.idle());
const editsJson = async (page) => JSON.parse(await page.evaluate(() => window.__ksmcmc.mapper.editsJson()));

/** Presses a shortcut with the focus on the page body (not in a text field). */
async function key(page, k) {
  await page.evaluate(() => document.activeElement?.blur());
  await page.keyboard.press(k);
}

/** Runs `n` Steps (the iterations per frame each) and waits until the page has drawn them. */
async function steps(page, n) {
  const from = (await snap(page)).iteration;
  for (let i = 0; i < n; i++) await key(page, 's');
  await page.waitForFunction((want) => window.__ksmcmc.snapshot().iteration >= want, from + n * 1000);
  await idle(page);
}

/** The best world's rooms and its labels (room id per cell), read from the worker. */
async function world(page) {
  return page.evaluate(async () => {
    const rooms = JSON.parse(await window.__ksmcmc.mapper.roomsJson());
    const pgm = await window.__ksmcmc.mapper.labelsPgm();
    const head = new TextDecoder().decode(pgm.subarray(0, 64)).match(/^P5\s+(\d+)\s+(\d+)\s+\d+\s/);
    const [w, h] = [Number(head[1]), Number(head[2])];
    const view = new DataView(pgm.buffer, pgm.byteOffset + head[0].length);
    const labels = Array.from({ length: w * h }, (_, i) => view.getUint16(2 * i));
    return { rooms, labels, width: w, height: h };
  });
}

/** A cell well inside room `id`: the one of its cells nearest their mean. */
function inside(w, id) {
  let sx = 0;
  let sy = 0;
  const cells = [];
  w.labels.forEach((l, i) => {
    if (l !== id) return;
    const c = [i % w.width, Math.floor(i / w.width)];
    cells.push(c);
    sx += c[0];
    sy += c[1];
  });
  assert.ok(cells.length > 0, `room ${id} has cells`);
  const [mx, my] = [sx / cells.length, sy / cells.length];
  return cells.reduce((best, c) => (Math.hypot(c[0] - mx, c[1] - my) < Math.hypot(best[0] - mx, best[1] - my) ? c : best));
}

const at = (w, [x, y]) => w.labels[y * w.width + x];

/** Clicks map cell (x, y) on the map canvas. */
async function clickCell(page, [x, y]) {
  await page.locator('#map').scrollIntoViewIfNeeded();
  const box = await page.locator('#map').boundingBox();
  const s = await snap(page);
  await page.mouse.click(box.x + ((x + 0.5) * box.width) / s.width, box.y + ((y + 0.5) * box.height) / s.height);
}

async function selected(page, room) {
  await page.waitForFunction((r) => document.getElementById('edit-selection').dataset.room === String(r), room);
}

async function expectAlert(page, pattern) {
  await page.waitForFunction(([src]) => !document.getElementById('message').hidden && new RegExp(src).test(document.getElementById('message-text').textContent), [pattern.source], { timeout: 10_000 });
}

/** Selects a room on the map, retypes it to hall and names it: the edit list shows both edits. */
async function retypeAndName(page, w) {
  const target = w.rooms.find((r) => r.type !== 'hall') ?? w.rooms[0];
  const p = inside(w, target.id);
  await clickCell(page, p);
  await selected(page, target.id);
  const ring = await page.evaluate(() => ['cx', 'cy'].map((k) => Number(document.querySelector('.edit-line circle.selected').getAttribute(k))));
  assert.deepEqual(ring, [p[0] + 0.5, p[1] + 0.5], 'the selected cell is marked on the map');
  await page.selectOption('#edit-type', 'hall');
  await page.click('#edit-type-apply');
  await page.waitForFunction(() => window.__ksmcmc.edits.length === 1);
  await page.fill('#edit-name', 'Kitchen');
  await page.press('#edit-name', 'Enter');
  await page.waitForFunction(() => window.__ksmcmc.edits.length === 2);
  const two = [
    { op: 'type', at: p, type: 'hall' },
    { op: 'name', at: p, name: 'Kitchen' },
  ];
  assert.deepEqual(await editsJson(page), two);
  assert.equal(await page.locator('#edit-list li').count(), 2);
  return { p, two };
}

/** After more steps the room at `p` is a hall named Kitchen, in the world and its Rooms row. */
async function checkNamed(page, p) {
  await steps(page, 3);
  const w = await world(page);
  const named = w.rooms.find((r) => r.id === at(w, p));
  assert.ok(named, `a room at ${p}`);
  assert.equal(named.type, 'hall');
  assert.equal(named.name, 'Kitchen');
  const row = page.locator(`#rooms tr[data-room="${named.id}"]`);
  assert.equal(await row.getAttribute('data-type'), 'hall');
  assert.match(await row.textContent(), /Kitchen/);
  return w;
}

/** Merges two neighbouring rooms (one selected by its Rooms row, the other clicked on the map): one room fewer. */
async function mergeOnMap(page, w, two) {
  const a = w.rooms.find((r) => r.opens_to.length > 0);
  assert.ok(a, 'a room with a neighbour');
  const b = a.opens_to[0];
  const pb = inside(w, b);
  const before = w.rooms.length;
  await page.click(`#rooms tr[data-room="${a.id}"]`);
  await selected(page, a.id);
  const pa = await page.evaluate(() => [window.__ksmcmc.selected.x, window.__ksmcmc.selected.y]);
  assert.equal(at(w, pa), a.id, 'the selected point lies in the selected room');
  await page.click('#edit-merge');
  assert.equal(await page.getAttribute('#edit-merge', 'aria-pressed'), 'true');
  await clickCell(page, pb);
  await page.waitForFunction(() => window.__ksmcmc.edits.length === 3 || !document.getElementById('message').hidden);
  assert.equal((await snap(page)).error, null);
  const three = [...two, { op: 'merge', at: [pa, pb] }];
  assert.deepEqual(await editsJson(page), three);
  await steps(page, 3);
  w = await world(page);
  assert.ok(w.rooms.length < before, `merging drops the room count: ${before} → ${w.rooms.length}`);
  assert.equal(at(w, pa), at(w, pb), 'both points lie in one room');
  assert.ok(at(w, pa) > 0);
  return { w, three };
}

/** Merges from the keyboard (Enter on a Rooms row, Merge with…, Enter on another row): the fourth edit merges them. */
async function mergeByKeyboard(page, w) {
  const c = w.rooms.find((r) => r.opens_to.length > 0);
  assert.ok(c, 'a room with a neighbour after the merge');
  await page.focus(`#rooms tr[data-room="${c.id}"]`);
  await page.keyboard.press('Enter');
  await selected(page, c.id);
  await page.focus('#edit-merge');
  await page.keyboard.press('Enter');
  await page.focus(`#rooms tr[data-room="${c.opens_to[0]}"]`);
  await page.keyboard.press('Enter');
  await page.waitForFunction(() => window.__ksmcmc.edits.length === 4);
  const four = await editsJson(page);
  assert.equal(four[3].op, 'merge');
  assert.equal(at(w, four[3].at[0]), c.id);
  assert.equal(at(w, four[3].at[1]), c.opens_to[0]);
}

/** Undo (button, then Ctrl+Z) takes off the last edit each time. */
async function undoThrice(page, two, three) {
  await page.click('#edit-undo');
  await page.waitForFunction(() => window.__ksmcmc.edits.length === 3);
  assert.deepEqual(await editsJson(page), three);
  await page.click('#edit-undo');
  await page.waitForFunction(() => window.__ksmcmc.edits.length === 2);
  assert.deepEqual(await editsJson(page), two);
  await key(page, 'Control+z');
  await page.waitForFunction(() => window.__ksmcmc.edits.length === 1);
  assert.deepEqual(await editsJson(page), two.slice(0, 1));
}

/** Splits by dragging a line on the map through `p`: the line shows while dragging and goes once the split is made. */
async function splitByDragging(page, p, two) {
  await page.click('#edit-split');
  await page.locator('#map').scrollIntoViewIfNeeded();
  const box = await page.locator('#map').boundingBox();
  const s = await snap(page);
  const px = ([x, y]) => [box.x + ((x + 0.5) * box.width) / s.width, box.y + ((y + 0.5) * box.height) / s.height];
  const [from, to] = [[p[0] - 3, p[1]], [p[0] + 3, p[1]]];
  await page.mouse.move(...px(from));
  await page.mouse.down();
  await page.mouse.move(...px(to), { steps: 4 });
  assert.equal(await page.getAttribute('.edit-line', 'data-split'), 'drawing', 'the line is drawn while dragging');
  const drawn = await page.evaluate(() => ['x1', 'y1', 'x2', 'y2'].map((k) => Number(document.querySelector('.edit-line line').getAttribute(k))));
  assert.deepEqual(drawn, [from[0] + 0.5, from[1] + 0.5, to[0] + 0.5, to[1] + 0.5]);
  await page.mouse.up();
  await page.waitForFunction(() => window.__ksmcmc.edits.length === 2);
  assert.deepEqual(await editsJson(page), [two[0], { op: 'split', line: [from, to] }]);
  assert.equal(await page.getAttribute('.edit-line', 'data-split'), '', 'the line goes once the split is made');
}

/** Export, clear, import: the same list. */
async function exportClearImport(page) {
  const exported = await download(page, '#edit-export');
  assert.equal(exported.name, 'edits.json');
  const kept = await editsJson(page);
  assert.deepEqual(JSON.parse(exported.bytes.toString('utf8')), kept);
  await page.click('#edit-clear');
  await page.waitForFunction(() => window.__ksmcmc.edits.length === 0);
  assert.deepEqual(await editsJson(page), []);
  await page.setInputFiles('#edit-import', { name: 'edits.json', mimeType: 'application/json', buffer: exported.bytes });
  await page.waitForFunction((n) => window.__ksmcmc.edits.length === n, kept.length);
  assert.deepEqual(await editsJson(page), kept);
  return kept;
}

/** Bad imports show an alert and change nothing. */
async function badImports(page, kept) {
  await page.setInputFiles('#edit-import', { name: 'bad.json', mimeType: 'application/json', buffer: Buffer.from('not json') });
  await expectAlert(page, /not JSON/);
  await page.setInputFiles('#edit-import', { name: 'off.json', mimeType: 'application/json', buffer: Buffer.from('[{"op":"type","at":[99999,5],"type":"hall"}]') });
  await expectAlert(page, /\S/);
  await page.waitForFunction(() => !/not JSON/.test(document.getElementById('message-text').textContent));
  assert.deepEqual(await editsJson(page), kept);
  await page.click('#message-close');
}

test('edit rooms: retype, name, merge, undo, export/import, Reset, bad imports', async () => {
  const page = await openPage(env, 'mapper.html?sample=office-small&seed=3&ipf=1000');
  await page.waitForFunction(() => window.__ksmcmc.snapshot().width > 0);
  await idle(page);
  await steps(page, 6);
  let w = await world(page);
  assert.ok(w.rooms.length >= 3, `the chain found rooms: ${w.rooms.length}`);

  const { p, two } = await retypeAndName(page, w);
  w = await checkNamed(page, p);
  const merged = await mergeOnMap(page, w, two);
  await mergeByKeyboard(page, merged.w);
  await undoThrice(page, two, merged.three);
  await splitByDragging(page, p, two);
  const kept = await exportClearImport(page);

  // Reset keeps the edits.
  await key(page, 'r');
  await page.waitForFunction(() => window.__ksmcmc.snapshot().iteration === 0);
  await idle(page);
  assert.deepEqual(await editsJson(page), kept);
  assert.equal(await page.locator('#edit-list li').count(), kept.length);

  await badImports(page, kept);

  // The section fits a 390 px phone.
  await page.setViewportSize({ width: 390, height: 800 });
  const overflow = await page.evaluate(() => document.documentElement.scrollWidth - document.documentElement.clientWidth);
  assert.ok(overflow <= 0, `the page fits 390 px: overflows by ${overflow}`);

  const problems = page.problems;
  await page.context().close();
  assert.deepEqual(problems, [], 'the page logged errors');
});
