#!/usr/bin/env node
// Copies the product's sample maps (samples/*/map.pgm, map.yaml, truth.json) into www/samples/
// for the live mapper page, and writes www/samples/index.json listing them:
//   [{ "name": "office-small", "width": 400, "height": 300, "description": "..." }, ...]
// Descriptions come from the table in samples/README.md, sizes from the PGM headers.
// Usage: node scripts/www-samples.mjs [samples-dir] [out-dir]

import { copyFileSync, existsSync, mkdirSync, readdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';

const src = process.argv[2] ?? 'samples';
const out = process.argv[3] ?? 'www/samples';
const FILES = ['map.pgm', 'map.yaml', 'truth.json'];

/** Width and height from a PGM header (P2 or P5), skipping comments. */
export function pgmSize(bytes) {
  const head = Buffer.from(bytes.subarray(0, 512)).toString('latin1').replace(/#[^\n]*\n/g, ' ');
  const m = /^P[25]\s+(\d+)\s+(\d+)/.exec(head);
  if (!m) throw new Error('not a PGM');
  return [Number(m[1]), Number(m[2])];
}

/** `{ name: description }` from the README's table rows: | `name` | size | description |. */
export function descriptions(readme) {
  const out = {};
  for (const line of readme.split('\n')) {
    const m = /^\|\s*`([\w-]+)`\s*\|[^|]*\|\s*(.+?)\s*\|\s*$/.exec(line);
    if (m) out[m[1]] = m[2].replace(/`/g, '');
  }
  return out;
}

function main() {
  const readme = existsSync(join(src, 'README.md')) ? readFileSync(join(src, 'README.md'), 'utf8') : '';
  const text = descriptions(readme);
  const names = readdirSync(src, { withFileTypes: true })
    .filter((d) => d.isDirectory() && existsSync(join(src, d.name, 'map.pgm')) && existsSync(join(src, d.name, 'map.yaml')))
    .map((d) => d.name)
    .sort();
  rmSync(out, { recursive: true, force: true });
  const index = [];
  for (const name of names) {
    mkdirSync(join(out, name), { recursive: true });
    for (const f of FILES) {
      if (existsSync(join(src, name, f))) copyFileSync(join(src, name, f), join(out, name, f));
    }
    const [width, height] = pgmSize(readFileSync(join(src, name, 'map.pgm')));
    index.push({ name, width, height, description: text[name] ?? '', truth: existsSync(join(src, name, 'truth.json')) });
  }
  writeFileSync(join(out, 'index.json'), `${JSON.stringify(index, null, 2)}\n`);
  console.log(`${out}/: ${index.length} samples (${index.map((s) => s.name).join(', ')})`);
}

if (import.meta.url === `file://${process.argv[1]}`) main();
