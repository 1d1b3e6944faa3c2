// Reading a plan up close (issue 12): zoom and pan by wheel, keys, pinch and drag on the live
// mapper, the table-top page and the mount() embed (www/lib/viewport.js), painting that lands
// on the cell under the pointer when zoomed in, and the room under the pointer, or in focus in
// the Rooms table, shown with its type, area, doors and type marginals (www/lib/room-info.js).

import { after, before, describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { done, openPage, snap, startBrowser, until } from './harness.mjs';

let env;
before(async () => {
  env = await startBrowser();
});
after(async () => {
  await env?.close();
});

/** Waits until the mapper has drawn the chain's latest state and waits for nothing. */
const idle = (page) => page.evaluate(() => window.__ksmcmc.idle());

async function openMapper(query = '', viewport) {
  const page = await openPage(env, `mapper.html${query}`, viewport);
  await page.waitForFunction(() => window.__ksmcmc.snapshot().width > 0);
  await idle(page);
  return page;
}

/** The map canvas's box on screen, scrolled into view. */
async function mapBox(page, selector = '#map') {
  await page.locator(selector).scrollIntoViewIfNeeded();
  return page.locator(selector).boundingBox();
}

/** The map alone (no world), so that the picture's pixels are the map's cells. */
async function mapOnly(page) {
  await page.check('input[name="show"][value="none"]');
  await idle(page);
}

/** Keeps the map canvas's pixels in the page (window.__kept) to compare with later. */
const keep = (page) =>
  page.evaluate(() => {
    const c = document.getElementById('map');
    window.__kept = { width: c.width, height: c.height, data: c.getContext('2d').getImageData(0, 0, c.width, c.height).data };
  });

/**
 * Compares the map canvas with the kept pixels as seen through a zoom by `z` about backing
 * pixel (px, py): the share of pixels (among those either shows as a wall or as unknown) whose
 * class (dark, gray, light) matches the kept pixel at the zoomed-out position, and the same
 * share for the unmoved position.
 */
const compareZoomed = (page, px, py, z) =>
  page.evaluate(([px, py, z]) => {
    const c = document.getElementById('map');
    const now = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    const { width, height, data } = window.__kept;
    const cls = (d, i) => {
      const lum = (d[i] + d[i + 1] + d[i + 2]) / 3;
      return lum < 64 ? 0 : lum > 240 ? 2 : 1;
    };
    let n = 0;
    let mapped = 0;
    let same = 0;
    for (let y = 0; y < height; y += 2) {
      for (let x = 0; x < width; x += 2) {
        const sx = Math.floor(px + (x + 0.5 - px) / z);
        const sy = Math.floor(py + (y + 0.5 - py) / z);
        const a = cls(now, 4 * (y * width + x));
        // Edges blur by a pixel when a picture is scaled: a kept pixel next to the position
        // counts.
        const near = (cx, cy) => {
          const out = new Set();
          for (let dy = -1; dy <= 1; dy++) {
            for (let dx = -1; dx <= 1; dx++) {
              const qx = Math.min(width - 1, Math.max(0, cx + dx));
              const qy = Math.min(height - 1, Math.max(0, cy + dy));
              out.add(cls(data, 4 * (qy * width + qx)));
            }
          }
          return out;
        };
        const b = near(sx, sy);
        if (a === 2 && b.size === 1 && b.has(2)) continue;
        n++;
        if (b.has(a)) mapped++;
        if (near(x, y).has(a)) same++;
      }
    }
    return { n, mapped: mapped / n, same: same / n };
  }, [px, py, z]);

describe('Zoom and pan on the live mapper', () => {
  test('the wheel zooms about the cursor and the worker draws more pixels per cell', async () => {
    const page = await openMapper();
    await mapOnly(page);
    const before = await snap(page);
    assert.deepEqual(before.view, { zoom: 1, cx: 0.5, cy: 0.5 });
    assert.equal(before.drawScale, before.scale);
    await keep(page);
    const box = await mapBox(page);
    const [fx, fy] = [0.3, 0.4];
    await page.mouse.move(box.x + fx * box.width, box.y + fy * box.height);
    await page.mouse.wheel(0, -300);
    await until(page, (s) => s.view.zoom > 1.5 && s.drawScale > s.scale);
    // The pointer leaves, and with it the highlight of the room under it.
    await page.mouse.move(box.x - 10, box.y - 10);
    await until(page, (s) => s.room === 0);
    await idle(page);
    const after = await snap(page);
    const z = after.view.zoom;
    // The point under the cursor stays there (fx = 0.5 + (u - cx) z with u = fx at zoom 1).
    // (to a pixel: the mouse is at whole pixels).
    const px = 1 / box.width;
    assert.ok(Math.abs(0.5 + (fx - after.view.cx) * z - fx) < px && Math.abs(0.5 + (fy - after.view.cy) * z - fy) < px, JSON.stringify(after.view));
    // And the picture shows it: walls and unknown cells are where the zoom about the cursor
    // puts them, not where they were.
    const { width, height } = await page.evaluate(() => ({ width: document.getElementById('map').width, height: document.getElementById('map').height }));
    const cmp = await compareZoomed(page, fx * width, fy * height, z);
    assert.ok(cmp.n > 1000, `enough non-free pixels to compare: ${cmp.n}`);
    assert.ok(cmp.mapped > 0.85, `the zoomed picture is the map enlarged ${z.toFixed(2)} times about the cursor: ${JSON.stringify(cmp)}`);
    assert.ok(cmp.same < cmp.mapped - 0.2, `and no longer the picture as it was: ${JSON.stringify(cmp)}`);
    // The picture is the worker's, at the new scale: canvas pixels per map cell are unchanged
    // (the canvas holds the whole map at `scale`), and the picture it draws has more.
    assert.equal(width, after.width * after.scale);

    // Scrolling back out returns to the whole map, and the picture as it was.
    await page.mouse.move(box.x + fx * box.width, box.y + fy * box.height);
    await page.mouse.wheel(0, 2000);
    await until(page, (s) => s.view.zoom === 1 && s.drawScale === s.scale);
    await page.mouse.move(box.x - 10, box.y - 10);
    await until(page, (s) => s.room === 0);
    await idle(page);
    const back = await compareZoomed(page, 0, 0, 1);
    assert.equal(back.mapped, 1, 'the whole map again, pixel class for pixel class');
    await done(page);
  });

  test('keys zoom, pan and reset with the map focused; the buttons do the same', async () => {
    const page = await openMapper();
    await mapOnly(page);
    await keep(page);
    const hash = () => page.evaluate(() => {
      const c = document.getElementById('map');
      const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
      let h = 0;
      for (let i = 0; i < d.length; i++) h = (h * 31 + d[i]) >>> 0;
      return h;
    });
    const original = await hash();
    await page.focus('#map');
    await page.keyboard.press('+');
    await until(page, (s) => Math.abs(s.view.zoom - 1.5) < 1e-9 && s.view.cx === 0.5 && s.view.cy === 0.5);
    await page.keyboard.press('+');
    await until(page, (s) => Math.abs(s.view.zoom - 2.25) < 1e-9);
    await idle(page);
    assert.notEqual(await hash(), original, 'zoomed in');
    await page.keyboard.press('ArrowRight');
    await until(page, (s) => s.view.cx > 0.5);
    const right = (await snap(page)).view;
    assert.ok(Math.abs(right.cx - (0.5 + 0.125 / 2.25)) < 1e-9, `an arrow moves an eighth of the view: ${JSON.stringify(right)}`);
    await page.keyboard.press('-');
    await until(page, (s) => Math.abs(s.view.zoom - 1.5) < 1e-9);
    await page.keyboard.press('0');
    await until(page, (s) => s.view.zoom === 1 && s.view.cx === 0.5 && s.view.cy === 0.5);
    await idle(page);
    assert.equal(await hash(), original, '0 shows the whole map as before, pixel for pixel');
    // The space and R keys still belong to the chain.
    await page.keyboard.press('s');
    await until(page, (s) => s.iteration === 500);

    // The buttons under the map.
    assert.equal(await page.isDisabled('#zoom-bar button[aria-label^="Zoom out"]'), true, 'nothing to zoom out of');
    await page.click('#zoom-bar button[aria-label^="Zoom in"]');
    await until(page, (s) => Math.abs(s.view.zoom - 1.5) < 1e-9);
    assert.match(await page.textContent('#zoom-bar button[data-zoom="fit"]'), /150 %/);
    await page.click('#zoom-bar button[data-zoom="fit"]');
    await until(page, (s) => s.view.zoom === 1);
    await done(page);
  });

  test('a drag pans the zoomed map; a pinch of two touches zooms about their midpoint', async () => {
    const page = await openMapper('', { width: 1280, height: 900 });
    const box = await mapBox(page);
    await page.focus('#map');
    await page.keyboard.press('+');
    await page.keyboard.press('+');
    await until(page, (s) => Math.abs(s.view.zoom - 2.25) < 1e-9);
    const cx = box.x + box.width / 2;
    const cy = box.y + box.height / 2;
    await page.mouse.move(cx, cy);
    await page.mouse.down();
    await page.mouse.move(cx - 100, cy - 50, { steps: 5 });
    await page.mouse.up();
    const dragged = (await snap(page)).view;
    assert.ok(Math.abs(dragged.cx - (0.5 + 100 / box.width / 2.25)) < 1e-6, `dragged left: the view moved right ${JSON.stringify(dragged)}`);
    assert.ok(Math.abs(dragged.cy - (0.5 + 50 / box.height / 2.25)) < 1e-6, JSON.stringify(dragged));
    await page.keyboard.press('0');
    await until(page, (s) => s.view.zoom === 1);

    // Two touches moving apart: Chromium's touch input, as a phone sends it.
    const cdp = await page.context().newCDPSession(page);
    const mx = box.x + box.width * 0.6;
    const my = box.y + box.height * 0.5;
    const touch = (type, d) =>
      cdp.send('Input.dispatchTouchEvent', {
        type,
        touchPoints: type === 'touchEnd' ? [] : [{ x: mx - d, y: my, id: 1 }, { x: mx + d, y: my, id: 2 }],
      });
    await touch('touchStart', 40);
    for (const d of [50, 60, 70, 80]) await touch('touchMove', d);
    await touch('touchEnd', 0);
    const pinched = (await snap(page)).view;
    assert.ok(Math.abs(pinched.zoom - 2) < 0.01, `fingers twice as far apart: zoom ${pinched.zoom}`);
    // The content under the midpoint (0.6, 0.5 of the map) stays under it.
    assert.ok(Math.abs(0.5 + (0.6 - pinched.cx) * pinched.zoom - 0.6) < 1 / box.width, JSON.stringify(pinched));
    await done(page);
  });

  test('painting while zoomed in lands on the cell under the pointer', async () => {
    const page = await openMapper();
    const s0 = await snap(page);
    await page.evaluate(() => {
      const b = document.getElementById('brush');
      b.value = '1';
      b.dispatchEvent(new Event('input'));
    });
    await page.evaluate(() => document.activeElement?.blur());
    await page.keyboard.press('p');
    await page.focus('#map');
    for (let i = 0; i < 3; i++) await page.keyboard.press('+');
    await page.keyboard.press('ArrowLeft');
    await page.keyboard.press('ArrowUp');
    const { view } = await snap(page);
    assert.ok(view.zoom > 3 && view.cx < 0.5 && view.cy < 0.5, JSON.stringify(view));
    // A free cell inside the view, away from its centre.
    const before = await page.evaluate(() => Array.from(window.__ksmcmc.map.cells()));
    const W = s0.width;
    const H = s0.height;
    const inView = (x, y) => {
      const fx = 0.5 + ((x + 0.5) / W - view.cx) * view.zoom;
      const fy = 0.5 + ((y + 0.5) / H - view.cy) * view.zoom;
      return fx > 0.1 && fx < 0.35 && fy > 0.6 && fy < 0.9 ? [fx, fy] : null;
    };
    let target = null;
    for (let y = 0; y < H && !target; y++) {
      for (let x = 0; x < W && !target; x++) {
        const at = inView(x, y);
        if (at && before[y * W + x] === 0) target = { x, y, at };
      }
    }
    assert.ok(target, 'a free cell in the lower left of the view');
    const box = await mapBox(page);
    const [fx, fy] = target.at;
    // Without the view, the same point would be another cell.
    const naive = [Math.floor(fx * W), Math.floor(fy * H)];
    assert.notDeepEqual(naive, [target.x, target.y]);
    await page.mouse.click(box.x + fx * box.width, box.y + fy * box.height);
    await until(page, (s, it) => window.__ksmcmc.map.cells()[it] === 2, target.y * W + target.x);
    await idle(page);
    const after = await page.evaluate(() => Array.from(window.__ksmcmc.map.cells()));
    const changed = after.map((v, i) => (v !== before[i] ? i : -1)).filter((i) => i >= 0);
    assert.deepEqual(changed, [target.y * W + target.x], 'exactly the cell under the pointer was painted');
    assert.equal(after[naive[1] * W + naive[0]], before[naive[1] * W + naive[0]]);
    assert.equal((await snap(page)).view.zoom, view.zoom, 'the stroke keeps the zoom');
    await done(page);
  });
});

/**
 * Rooms of the page's best world with their details, as the page reads them from the worker
 * while someone points at rooms (here: the mouse on the map, or `during`).
 */
async function roomDetails(page, during) {
  if (during) await during();
  else {
    const box = await mapBox(page);
    await page.mouse.move(box.x + 2, box.y + 2);
  }
  await page.waitForFunction(() => window.__ksmcmc.roomDetails !== null, null, { timeout: 10_000 });
  return page.evaluate(() => {
    const d = window.__ksmcmc.roomDetails;
    return { rooms: window.__ksmcmc.rooms, types: d.types, labels: Array.from(d.labels) };
  });
}

/** A cell of room `id` whose 7 x 7 neighbourhood is all that room. */
function innerCell(labels, W, H, id) {
  for (let y = 3; y < H - 3; y++) {
    for (let x = 3; x < W - 3; x++) {
      let ok = true;
      for (let dy = -3; dy <= 3 && ok; dy++) for (let dx = -3; dx <= 3 && ok; dx++) ok = labels[(y + dy) * W + x + dx] === id;
      if (ok) return [x, y];
    }
  }
  return null;
}

describe('The room under the pointer', () => {
  test('hovering a room shows its id, type, area, doors and type marginals; clicking pins it', async () => {
    const page = await openMapper();
    for (let i = 0; i < 6; i++) {
      await page.evaluate(() => document.activeElement?.blur());
      await page.keyboard.press('s');
      await idle(page);
    }
    const s = await snap(page);
    const { rooms, types, labels } = await roomDetails(page);
    assert.equal(labels.length, s.width * s.height);
    assert.deepEqual(types.map((t) => t.id), rooms.map((r) => r.id), 'a type row per room');
    // A room of one unit: its marginals are its unit's, whose most probable type is its type.
    const row = types.find((t) => t.units.length === 1 && t.marginals && innerCell(labels, s.width, s.height, t.id));
    assert.ok(row, `a one-unit room with marginals: ${JSON.stringify(types)}`);
    const room = rooms.find((r) => r.id === row.id);
    const [x, y] = innerCell(labels, s.width, s.height, room.id);
    const box = await mapBox(page);
    await page.mouse.move(box.x + ((x + 0.5) / s.width) * box.width, box.y + ((y + 0.5) / s.height) * box.height);
    await page.waitForSelector(`#room-info:not([hidden])[data-room="${room.id}"]`, { timeout: 5000 });
    const info = await page.evaluate(() => {
      const b = document.getElementById('room-info');
      return {
        title: b.querySelector('.room-info-title').textContent,
        area: b.querySelector('.room-info-area').textContent,
        doors: b.querySelector('.room-info-doors').textContent,
        opens: b.querySelector('.room-info-opens').textContent,
        units: b.querySelector('.room-info-units').textContent,
        marginals: [...b.querySelectorAll('.room-info-marginals tr')].map((tr) => [tr.dataset.type, Number(tr.querySelector('td.p').textContent)]),
        visible: b.getBoundingClientRect().width > 0,
      };
    });
    assert.equal(info.title, `Room ${room.id} · ${room.type}`);
    // Rounded as the page rounds for reading (half up on the decimal digits, not toFixed's binary).
    const area = room.area_m2.toLocaleString('en-US', { minimumFractionDigits: 1, maximumFractionDigits: 1 });
    assert.equal(info.area, `${area} m²`);
    // Each door says where it leads: the other room listing it (issue 33), ids that read as ids.
    const leadsTo = (d) => rooms.filter((r) => r.id !== room.id && r.doors.includes(d)).map((r) => `room ${r.id}`);
    const doorTexts = room.doors.map((d) => (leadsTo(d).length ? `door ${d} to ${leadsTo(d).join(' and ')}` : `door ${d} within the room`));
    assert.equal(info.doors, room.doors.length ? doorTexts.join(', ') : 'no doors');
    assert.ok(room.doors.every((d) => leadsTo(d).every((t) => room.opens_to.includes(Number(t.slice(5))))), 'a door leads to a room it opens to');
    assert.equal(info.opens, `opens to: ${room.opens_to.length ? room.opens_to.map((r) => `room ${r}`).join(', ') : 'none'}`);
    assert.equal(info.units, `units: ${row.units[0].type} ${row.units[0].id}`, 'the unit label in full');
    assert.deepEqual(info.marginals.map(([t]) => t), ['room', 'corridor', 'hall', 'other']);
    for (const [t, p] of info.marginals) {
      assert.ok(p >= 0 && p <= 1, `${t}: ${p}`);
      assert.ok(Math.abs(p - row.marginals[t]) <= 0.005, `${t}: shown ${p}, inferred ${row.marginals[t]}`);
    }
    const top = Object.entries(row.marginals).sort((a, b) => b[1] - a[1])[0][0];
    assert.equal(top, room.type, 'the most probable type is the room\'s type');
    const sum = Object.values(row.marginals).reduce((a, b) => a + b, 0);
    console.log(`room ${room.id} (${room.type}): marginals ${JSON.stringify(row.marginals)}, sum ${sum.toFixed(3)}`);
    assert.equal((await snap(page)).room, room.id, 'the room is highlighted');

    // Moving off the map hides it; a click pins it, and it stays when the pointer leaves.
    await page.mouse.move(box.x - 20, box.y - 20);
    await page.waitForSelector('#room-info', { state: 'hidden' });
    await page.mouse.click(box.x + ((x + 0.5) / s.width) * box.width, box.y + ((y + 0.5) / s.height) * box.height);
    await page.mouse.move(box.x - 20, box.y - 20);
    await page.waitForTimeout(100);
    assert.deepEqual([(await snap(page)).roomPinned, await page.isVisible('#room-info')], [true, true]);
    await page.keyboard.press('Escape');
    await page.waitForSelector('#room-info', { state: 'hidden' });
    await done(page);
  });

  test('focusing a row of the Rooms table highlights its room on the map and describes it', async () => {
    const page = await openMapper();
    for (let i = 0; i < 6; i++) {
      await page.evaluate(() => document.activeElement?.blur());
      await page.keyboard.press('s');
      await idle(page);
    }
    await mapOnly(page);
    const s = await snap(page);
    const rooms = await page.evaluate(() => window.__ksmcmc.rooms);
    assert.equal(await page.evaluate(() => window.__ksmcmc.roomDetails), null, 'no details read while nobody points at rooms');
    const room = rooms.reduce((a, b) => (b.area_m2 > a.area_m2 ? b : a));
    await keep(page);
    // The keyboard alone: the details are read when the row takes the focus.
    const { labels } = await roomDetails(page, () => page.focus(`#rooms tbody tr[data-room="${room.id}"]`));
    await page.waitForSelector(`#room-info:not([hidden])[data-room="${room.id}"]`, { timeout: 5000 });
    assert.match(await page.getAttribute('#room-info', 'aria-label'), new RegExp(`^Room ${room.id}, ${room.type}, `));
    // The canvas changed only over the room's cells (at `scale` pixels per cell).
    const changed = await page.evaluate(() => {
      const c = document.getElementById('map');
      const now = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
      const { data, width } = window.__kept;
      const out = [];
      for (let i = 0; i < now.length; i += 4) {
        if (now[i] !== data[i] || now[i + 1] !== data[i + 1] || now[i + 2] !== data[i + 2]) out.push((i / 4) % width, Math.floor(i / 4 / width));
      }
      return out;
    });
    assert.ok(changed.length > 200, `the room is highlighted: ${changed.length / 2} pixels changed`);
    let outside = 0;
    for (let i = 0; i < changed.length; i += 2) {
      const [cx, cy] = [Math.floor(changed[i] / s.scale), Math.floor(changed[i + 1] / s.scale)];
      if (labels[cy * s.width + cx] !== room.id) outside++;
    }
    assert.equal(outside, 0, 'no pixel outside the room changed');
    // Tab to the next row: its room instead.
    await page.keyboard.press('Tab');
    const next = await page.evaluate(() => document.activeElement.dataset.room);
    assert.ok(next && Number(next) !== room.id);
    await page.waitForSelector(`#room-info:not([hidden])[data-room="${next}"]`, { timeout: 5000 });
    await page.keyboard.press('Escape');
    await page.waitForSelector('#room-info', { state: 'hidden' });
    await done(page);
  });
});

describe('Zoom on the table-top page and in the embed', () => {
  test('table-top: the wheel zooms the camera view, keys the scene graph, Fit resets', async () => {
    const page = await openPage(env, 'tabletop.html');
    const snapTt = () => page.evaluate(() => window.__ksmcmc.snapshot());
    const width = await page.evaluate(() => document.getElementById('view').width);
    const box = await mapBox(page, '#view');
    await page.mouse.move(box.x + box.width * 0.25, box.y + box.height * 0.25);
    await page.mouse.wheel(0, -300);
    await page.waitForFunction(() => window.__ksmcmc.snapshot().view.zoom > 1.5);
    const s = await snapTt();
    assert.equal(s.viewDetail, 2, 'the camera view is drawn with twice the pixels');
    assert.ok(Math.abs(0.5 + (0.25 - s.view.cx) * s.view.zoom - 0.25) < 1 / box.width, `the point under the cursor stays: ${JSON.stringify(s.view)}`);
    assert.equal(await page.evaluate(() => document.getElementById('view').width), width, 'the canvas keeps its size');
    await page.focus('#graph');
    await page.keyboard.press('+');
    await page.waitForFunction(() => Math.abs(window.__ksmcmc.snapshot().graphView.zoom - 1.5) < 1e-9);
    await page.click('[aria-label="Zoom the camera view"] button[data-zoom="fit"]');
    await page.waitForFunction(() => window.__ksmcmc.snapshot().view.zoom === 1);
    assert.equal((await snapTt()).viewDetail, 1);
    await done(page);
  });

  test('mount(): the map zooms by wheel and keys, and its Fit button shows all of it', async () => {
    const page = await openPage(env, 'embed.html');
    await page.waitForFunction(() => window.__widget?.stats().iteration > 500, null, { timeout: 20_000 });
    await page.click('#demo button:has-text("Pause")');
    const box = await mapBox(page, '#demo canvas.ksmcmc-map');
    await page.mouse.move(box.x + box.width * 0.7, box.y + box.height * 0.3);
    await page.mouse.wheel(0, -300);
    const v = await page.evaluate(() => window.__widget.view);
    assert.ok(v.zoom > 1.5, JSON.stringify(v));
    assert.ok(Math.abs(0.5 + (0.7 - v.cx) * v.zoom - 0.7) < 1 / box.width, `the point under the cursor stays: ${JSON.stringify(v)}`);
    await page.focus('#demo canvas.ksmcmc-map');
    await page.keyboard.press('-');
    assert.ok(Math.abs((await page.evaluate(() => window.__widget.view.zoom)) - v.zoom / 1.5) < 1e-9);
    await page.click('#demo .ksmcmc-zoom button[data-zoom="fit"]');
    assert.equal(await page.evaluate(() => window.__widget.view.zoom), 1);
    await done(page);
  });
});
