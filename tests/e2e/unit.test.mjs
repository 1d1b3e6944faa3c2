// The page's pure helpers (www/lib), without a browser.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { brushOffsets, cellAt, line, stamp, strokeTo, TOOLS } from '../../www/lib/paint.js';
import { matchImage, parseSeed, pickYamlImage, planOpen, stem, yamlImageName } from '../../www/lib/files.js';
import { errorSpan, errorText } from '../../www/lib/rules-editor.js';
import { naturalCompare } from '../../www/lib/natural.js';
import { describeEdit, parseEdits } from '../../www/lib/edits.js';
import { View, detailScale, MAX_ZOOM } from '../../www/lib/viewport.js';

test('unit names sort by their numbers', () => {
  assert.deepEqual(['U10', 'U2', 'U1', 'U21', 'U3'].sort(naturalCompare), ['U1', 'U2', 'U3', 'U10', 'U21']);
  assert.ok(naturalCompare('U9', 'U10') < 0);
  assert.equal(naturalCompare('U7', 'U7'), 0);
});

test('brushes are round and centred', () => {
  assert.deepEqual(brushOffsets(1), [[0, 0]]);
  assert.equal(brushOffsets(2).length, 5);
  assert.equal(brushOffsets(3).length, 9);
  assert.equal(brushOffsets(0).length, 1);
  assert.equal(brushOffsets(NaN).length, 1);
  for (const s of [1, 2, 3, 5, 8, 64]) {
    const o = brushOffsets(s);
    assert.ok(o.some(([x, y]) => x === 0 && y === 0));
    assert.equal(o.reduce((a, [x]) => a + x, 0), 0, 'symmetric');
  }
  assert.deepEqual(brushOffsets(1000), brushOffsets(64), 'capped');
});

test('stamping paints, clips at the border and erases to the base', () => {
  const base = new Uint8Array(12).fill(1);
  const codes = base.slice();
  assert.equal(stamp(codes, base, 4, 3, 0, 0, brushOffsets(3), TOOLS.occupied), 4);
  assert.deepEqual([...codes], [2, 2, 1, 1, 2, 2, 1, 1, 1, 1, 1, 1]);
  assert.equal(stamp(codes, base, 4, 3, 0, 0, brushOffsets(3), TOOLS.occupied), 0, 'nothing new');
  assert.equal(stamp(codes, base, 4, 3, 9, 9, brushOffsets(3), TOOLS.free), 0, 'off the map');
  assert.equal(stamp(codes, base, 4, 3, 1, 1, brushOffsets(1), TOOLS.eraser), 1);
  assert.equal(codes[5], 1);
});

test('lines are continuous', () => {
  assert.deepEqual(line(0, 0, 3, 0), [[0, 0], [1, 0], [2, 0], [3, 0]]);
  assert.deepEqual(line(2, 2, 2, 2), [[2, 2]]);
  const l = line(0, 0, 7, -3);
  assert.deepEqual(l[0], [0, 0]);
  assert.deepEqual(l.at(-1), [7, -3]);
  for (let i = 1; i < l.length; i++) {
    assert.ok(Math.abs(l[i][0] - l[i - 1][0]) <= 1 && Math.abs(l[i][1] - l[i - 1][1]) <= 1);
  }
  const base = new Uint8Array(50).fill(1);
  const codes = base.slice();
  assert.equal(strokeTo(codes, base, 10, 5, [0, 2], [9, 2], brushOffsets(1), 0), 10);
});

test('pointer positions map to cells', () => {
  const shown = { width: 200, height: 100 };
  assert.deepEqual(cellAt(0, 0, shown, 20, 10), [0, 0]);
  assert.deepEqual(cellAt(199.9, 99.9, shown, 20, 10), [19, 9]);
  assert.deepEqual(cellAt(-5, 500, shown, 20, 10), [0, 9]);
  assert.deepEqual(cellAt(105, 55, shown, 20, 10), [10, 5]);
});

test('a map.yaml is matched to the image it names', () => {
  assert.equal(yamlImageName('resolution: 0.05\nimage: lab.pgm\n'), 'lab.pgm');
  assert.equal(yamlImageName('image: "my map.pgm"  # quoted\n'), 'my map.pgm');
  assert.equal(yamlImageName("image: 'a.png'\n"), 'a.png');
  assert.equal(yamlImageName('image: maps/lab.pgm # comment\n'), 'maps/lab.pgm');
  assert.equal(yamlImageName('resolution: 0.05\n'), null);
  assert.equal(yamlImageName('image:\n'), null);
  assert.equal(matchImage('maps/lab.pgm', ['x.png', 'lab.pgm']), 'lab.pgm');
  assert.equal(matchImage('LAB.PGM', ['lab.pgm']), 'lab.pgm');
  assert.equal(matchImage('lab.pgm', ['other.pgm']), null);
  assert.deepEqual(pickYamlImage('m.yaml', 'image: a.pgm\n', ['a.pgm']), { image: 'a.pgm' });
  assert.match(pickYamlImage('m.yaml', 'image: a.pgm\n', []).message, /select it together/);
  assert.match(pickYamlImage('m.yaml', 'image: a.pgm\n', ['b.pgm']).message, /"b\.pgm"/);
  assert.match(pickYamlImage('m.yaml', 'foo: 1\n', ['b.pgm']).message, /no `image:` line/);
});

test('picked files are planned', () => {
  assert.deepEqual(planOpen(['a.png']), { kind: 'image', image: 'a.png' });
  assert.deepEqual(planOpen(['m.yaml', 'a.pgm']), { kind: 'yaml', yaml: 'm.yaml', images: ['a.pgm'] });
  assert.deepEqual(planOpen(['m.YML']), { kind: 'yaml', yaml: 'm.YML', images: [] });
  assert.equal(planOpen([]).kind, 'error');
  assert.equal(planOpen(['a.png', 'b.png']).kind, 'error');
  assert.equal(planOpen(['a.yaml', 'b.yaml', 'c.pgm']).kind, 'error');
  assert.equal(stem('lab_ipa.png'), 'lab_ipa');
  assert.equal(stem('dir/x.tar.pgm'), 'x.tar');
  assert.equal(stem('.hidden'), '.hidden');
});

test('seeds are whole numbers, bigints above 2^53', () => {
  assert.equal(parseSeed(' 7 '), 7);
  assert.equal(parseSeed('0'), 0);
  assert.equal(parseSeed('9007199254740991'), Number.MAX_SAFE_INTEGER);
  assert.equal(parseSeed('9007199254740992'), 9007199254740992n);
  assert.equal(parseSeed('18446744073709551615'), 18446744073709551615n);
  for (const bad of ['', '-1', '1.5', '1e3', 'abc', '0x10']) assert.throws(() => parseSeed(bad), /whole number/);
});

// ---------------------------------------------------------------- live mapper helpers

import { readFileSync as readText } from 'node:fs';
import { cssSize, formatNumber, parseIterationsPerFrame, plotPoints, yRange } from '../../www/lib/plot.js';
import { SAMPLES, SYNTH_FLAGS, sampleRecipe } from '../../npm/samples.js';
import { descriptions, pgmSize } from '../../scripts/www-samples.mjs';

test('iterations per frame: auto or a whole number from 1 to 100000', () => {
  assert.equal(parseIterationsPerFrame('auto'), 'auto');
  assert.equal(parseIterationsPerFrame(' AUTO '), 'auto');
  assert.equal(parseIterationsPerFrame(''), 'auto');
  assert.equal(parseIterationsPerFrame('250'), 250);
  assert.equal(parseIterationsPerFrame('100000'), 100000);
  for (const bad of ['0', '-5', 'NaN', '2.5', '1e3', '100001', 'fast', 'Infinity']) {
    assert.throws(() => parseIterationsPerFrame(bad), /Iterations per frame: .* is not allowed/, bad);
  }
});

test('plots fit the trace into the box and thin out long traces', () => {
  assert.deepEqual(yRange([]), [0, 1]);
  assert.deepEqual(yRange([5, 5]), [4, 6]);
  assert.deepEqual(yRange([0, 10]), [-0.5, 10.5]);
  assert.deepEqual(yRange([NaN, 2, Infinity, 4]), [1.9, 4.1]);
  assert.deepEqual(yRange([3], [0, 1]), [0, 1]);
  assert.deepEqual(plotPoints([], [], 100, 50), []);
  assert.deepEqual(plotPoints([1], [1], 4, 4), [], 'no room inside the padding');
  const pts = plotPoints([0, 50, 100], [0, 5, 10], 108, 58, { pad: 4 });
  assert.deepEqual(pts[0], [4, 4 + 50 - (0.5 / 11) * 50]);
  assert.equal(pts[2][0], 104, 'the last point at the right edge');
  assert.ok(pts[2][1] < pts[1][1] && pts[1][1] < pts[0][1], 'larger values plot higher');
  const n = 100000;
  const xs = Array.from({ length: n }, (_, i) => i);
  const long = plotPoints(xs, xs, 208, 50);
  assert.ok(long.length <= 2 * 200 + 2, `${long.length} points for 200 pixels`);
  assert.equal(long.at(-1)[0], 204, 'the newest point is kept');
  const clamped = plotPoints([0, 1], [-5, 5], 20, 20, { pad: 0, range: [0, 1] });
  assert.deepEqual(clamped.map((p) => p[1]), [20, 0], 'values outside a fixed range stay on the frame');
  assert.equal(formatNumber(12345.678, 1), '12,345.7');
  assert.equal(formatNumber(NaN), '–');
});

test('a plot reads its size once, then as its ResizeObserver reports it', () => {
  // A stand-in observer: it records what it watches; `resize` calls it as a browser would.
  const watched = [];
  let callback = null;
  globalThis.ResizeObserver = class {
    constructor(cb) {
      callback = cb;
    }
    observe(el) {
      watched.push(el);
    }
  };
  try {
    let reads = 0;
    const el = {
      w: 300,
      get clientWidth() {
        reads++;
        return this.w;
      },
      clientHeight: 110,
    };
    assert.deepEqual(cssSize(el), { width: 300, height: 110 });
    el.w = 320;
    assert.deepEqual(cssSize(el), { width: 300, height: 110 }, 'no layout read between resizes');
    assert.equal(reads, 1);
    assert.deepEqual(watched, [el]);
    callback([{ target: el }]);
    assert.deepEqual(cssSize(el), { width: 320, height: 110 }, 'the resize is seen');
    assert.equal(watched.length, 1, 'observed once');
  } finally {
    delete globalThis.ResizeObserver;
  }
});

test('the embed\'s sample recipes are the commands in samples/README.md', () => {
  const readme = readText(new URL('../../samples/README.md', import.meta.url), 'utf8');
  const commands = readme.split('\n').filter((l) => l.startsWith('ksmcmc synth '));
  assert.equal(commands.length, Object.keys(SAMPLES).length, 'one recipe per sample');
  const byFlag = Object.fromEntries(Object.entries(SYNTH_FLAGS).map(([k, v]) => [v, k]));
  for (const line of commands) {
    const words = line.trim().split(/\s+/).slice(2);
    const opts = {};
    for (let i = 0; i < words.length; i += 2) opts[words[i]] = words[i + 1];
    const name = opts['--out'].split('/').pop();
    const recipe = sampleRecipe(name);
    assert.equal(recipe.seed, Number(opts['--seed']), `${name}: seed`);
    const config = {};
    for (const [flag, value] of Object.entries(opts)) {
      if (flag === '--seed' || flag === '--out') continue;
      assert.ok(byFlag[flag], `${name}: ${flag} has a config field in SYNTH_FLAGS`);
      config[byFlag[flag]] = Number(value);
    }
    assert.deepEqual(recipe.config, config, `${name}: config`);
    assert.equal(recipe.command, line.replace(/\s+--out\s+\S+/, '').trim(), `${name}: command`);
  }
  assert.throws(() => sampleRecipe('nope'), /unknown sample "nope"; the samples are office-small/);
  assert.throws(() => sampleRecipe('constructor'), /unknown sample/);
});

test('the page\'s sample index reads sizes and descriptions', () => {
  assert.deepEqual(pgmSize(Buffer.from('P5\n# made by hand\n400 300\n255\n')), [400, 300]);
  assert.deepEqual(pgmSize(Buffer.from('P2 3 1 255\n0 0 0\n')), [3, 1]);
  assert.throws(() => pgmSize(Buffer.from('P6 1 1 255\n')), /not a PGM/);
  const d = descriptions('| `map.pgm` | the map |\n| `office-small` | 400 x 300 | the defaults: `one` corridor |\n');
  assert.deepEqual(d, { 'office-small': 'the defaults: one corridor' });
});

test('the rules editor underlines the token at the parser\'s line and column', () => {
  const text = 'Room(u)\nlog(0.9/0.1) HaLi(p) => => Hall(p)\n0.5 Hall(x) ^';
  const at = (line, column) => {
    const s = errorSpan(text, line, column);
    return s && text.slice(s.start, s.end);
  };
  assert.equal(at(1, 1), 'Room', 'a word');
  assert.equal(at(1, 5), '(', 'one punctuation character');
  assert.equal(at(2, 25), '=>', 'a connective');
  assert.equal(at(2, 14), 'HaLi');
  assert.equal(at(2, 5), '0.9', 'a number');
  assert.equal(at(2, 3), 'g', 'from the column to the end of the word');
  const end = errorSpan(text, 3, 99);
  assert.deepEqual(end, { start: text.length, end: text.length }, 'past the end of the last line: an empty span at its end');
  const eol = errorSpan(text, 1, 8);
  assert.deepEqual(eol, { start: 7, end: 7 }, 'past the end of a line: its end, not the next line');
  for (const [l, c] of [[0, 1], [1, 0], [4, 1], [NaN, 1], [1.5, 2]]) assert.equal(errorSpan(text, l, c), null, `${l}:${c}`);
  assert.equal(errorText({ line: 2, column: 25, message: 'expected a formula' }), 'line 2, column 25: expected a formula');
  assert.equal(errorText({ line: 0, column: 0, message: 'too big' }), 'too big');
  assert.equal(errorText(null), '');
});

test('edits are worded and imported files checked for a list', () => {
  assert.equal(describeEdit({ op: 'merge', at: [[1, 2], [3, 4]] }), 'merge (1, 2) with (3, 4)');
  assert.equal(describeEdit({ op: 'split', line: [[0, 5], [9, 5]] }), 'split along (0, 5)–(9, 5)');
  assert.equal(describeEdit({ op: 'type', at: [7, 8], type: 'hall' }), '(7, 8) is a hall');
  assert.equal(describeEdit({ op: 'name', at: [7, 8], name: 'Kitchen' }), '(7, 8) is named “Kitchen”');
  assert.equal(describeEdit({ op: 'paint' }), '{"op":"paint"}');
  const list = [{ op: 'type', at: [1, 1], type: 'room' }];
  assert.deepEqual(parseEdits(JSON.stringify(list)), list);
  assert.deepEqual(parseEdits('[]'), []);
  assert.match(parseEdits('not json').message, /not JSON/);
  assert.match(parseEdits('{"op": "merge"}').message, /JSON list/);
});

test('a view zooms about a point, pans, and never leaves the picture', () => {
  const v = new View();
  assert.deepEqual(v.state(), { zoom: 1, cx: 0.5, cy: 0.5 });
  assert.deepEqual(v.toContent(0.3, 0.7), [0.3, 0.7], 'zoom 1: element and content agree');
  assert.equal(v.panBy(0.1, 0), false, 'nothing to pan at zoom 1');
  assert.equal(v.zoomAt(0.5), false, 'nothing to zoom out of');

  // Zooming about (0.2, 0.25) keeps the content there.
  const before = v.toContent(0.2, 0.25);
  assert.equal(v.zoomAt(2, 0.2, 0.25), true);
  const after = v.toContent(0.2, 0.25);
  assert.ok(Math.abs(after[0] - before[0]) < 1e-12 && Math.abs(after[1] - before[1]) < 1e-12, `${before} -> ${after}`);
  assert.equal(v.zoom, 2);
  const [fx, fy] = v.toElement(...before);
  assert.ok(Math.abs(fx - 0.2) < 1e-12 && Math.abs(fy - 0.25) < 1e-12, 'toElement inverts toContent');

  // Zooming about a point near the corner clamps the view to the picture.
  v.reset();
  v.zoomAt(4, 0.01, 0.99);
  assert.ok(Math.abs(v.cx - (0.01 + 0.49 / 4)) < 1e-12, 'about the point while it fits');
  assert.equal(v.panBy(0.5, -0.5), true);
  assert.deepEqual([v.cx, v.cy], [0.125, 0.875], 'the view touches the corner, no further');
  assert.equal(v.panBy(0.5, -0.5), false, 'cannot pan off the picture');
  assert.equal(v.panBy(-0.5, 0), true);
  assert.equal(v.cx, 0.125 + 0.5 / 4);

  // Limits.
  v.zoomAt(1e6);
  assert.equal(v.zoom, MAX_ZOOM);
  v.zoomAt(NaN);
  assert.ok(Number.isFinite(v.zoom) && v.zoom >= 1, 'a NaN factor does not break the view');
  v.zoom = Infinity;
  v.clamp();
  assert.ok(v.zoom === 1 || v.zoom === MAX_ZOOM);

  // The canvas transform draws content point (u, v) where toElement says.
  v.reset();
  v.zoomAt(3, 0.7, 0.4);
  const [a, , , d, e, f] = v.transform(600, 400, 300, 200);
  const [u, w] = [0.55, 0.45];
  const [ex, ey] = v.toElement(u, w);
  assert.ok(Math.abs(a * u * 300 + e - ex * 600) < 1e-9 && Math.abs(d * w * 200 + f - ey * 400) < 1e-9);

  // A pinch to zoom 2 with content (0.6, 0.5) under (0.6, 0.5): that point stays put.
  v.reset();
  v.pinchTo(0.6, 0.5, 2, 0.6, 0.5);
  assert.deepEqual(v.toElement(0.6, 0.5).map((x) => Math.round(x * 1e12) / 1e12), [0.6, 0.5]);
  // Centring a point out of view.
  assert.equal(v.reveal(0.05, 0.05), true);
  assert.deepEqual([v.cx, v.cy], [0.25, 0.25]);
  assert.equal(v.reveal(0.25, 0.25), false, 'already in view');
});

test('zoomed pictures get more pixels per cell within their limits', () => {
  assert.equal(detailScale(2, 1, 1000), 2);
  assert.equal(detailScale(2, 2.2, 1000), 5);
  assert.equal(detailScale(3, 16, 1000), 8, 'at most maxScale');
  assert.equal(detailScale(3, 4, 831_264, { maxPixels: 6_000_000 }), 2, 'Cartesium: at most 6 million pixels');
  assert.equal(detailScale(1, 1, 1e9), 1, 'never below 1');
  assert.equal(detailScale(NaN, 2, 10), 1);
});

// ---------------------------------------------------------------- the pages' house

import { readdirSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { checkShells, PAGES } from '../../scripts/check-shell.mjs';
import { scheduler, turnDue } from '../../www/lib/scheduler.js';

const WWW_DIR = fileURLToPath(new URL('../../www/', import.meta.url));

test('the seven pages share one shell: head, skip link, header with the nav, message box (scripts/check-shell.mjs)', () => {
  assert.equal(PAGES.length, 7);
  assert.deepEqual(checkShells(WWW_DIR), []);
});

test('no module of the pages is over 900 lines', () => {
  const long = [];
  for (const dir of ['', 'lib', 'mapper']) {
    for (const name of readdirSync(WWW_DIR + dir).filter((f) => f.endsWith('.js'))) {
      const path = `${dir ? `${dir}/` : ''}${name}`;
      const lines = readText(WWW_DIR + path, 'utf8').split('\n').length - 1;
      if (lines > 900) long.push(`www/${path}: ${lines} lines`);
    }
  }
  assert.deepEqual(long, []);
});

test("the workers' scheduler runs its loop once however often it is asked, and again when the loop asks", async () => {
  // Node keeps a MessagePort with a listener open: the channels made here are closed after.
  const Channel = globalThis.MessageChannel;
  const made = [];
  globalThis.MessageChannel = class extends Channel {
    constructor() {
      super();
      made.push(this);
    }
  };
  try {
    let runs = 0;
    let more = 2;
    let finish;
    const finished = new Promise((resolve) => {
      finish = resolve;
    });
    const schedule = scheduler(() => {
      runs++;
      if (more-- > 0) schedule();
      else finish();
    });
    schedule();
    schedule();
    schedule();
    assert.equal(runs, 0, 'not at once: at the next macrotask');
    await finished;
    await new Promise((resolve) => setTimeout(resolve, 20));
    assert.equal(runs, 3, 'three asks before the first run are one run, then the two the loop asked for');
  } finally {
    globalThis.MessageChannel = Channel;
    for (const c of made) c.port1.close();
  }
  // A turn (a picture, a rooms request) that took 1 s with a share of 0.5 waits 1 s of chain;
  // 100 ms with 0.25, 300 ms.
  assert.equal(turnDue(performance.now(), 1000, 0.5), false);
  assert.equal(turnDue(performance.now() - 1e6, 1000, 0.5), true);
  assert.equal(turnDue(performance.now() - 100, 100, 0.25), false);
  assert.equal(turnDue(performance.now() - 301, 100, 0.25), true);
  assert.equal(turnDue(0, 0, 0.3), true, 'the first turn is due at once');
});
