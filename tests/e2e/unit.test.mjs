// The page's pure helpers (www/lib), without a browser.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { brushOffsets, cellAt, line, stamp, strokeTo, TOOLS } from '../../www/lib/paint.js';
import { matchImage, parseSeed, pickYamlImage, planOpen, stem, yamlImageName } from '../../www/lib/files.js';

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
