#!/usr/bin/env node
// Writes pkg/package.json for the npm package that wasm-bindgen generated into pkg/.
// Usage: node scripts/pkg-json.mjs [Cargo.toml] [npm-dir] [module.js ...] [--modules NAME ...] > pkg/package.json
// Name, version, description and licence come from Cargo.toml's [package] section, so the
// npm package and the crate never disagree. The hand-written ES modules in npm/ (the `mount`
// embed and the sample recipes, copied into pkg/ by `make pkg`) are listed as exports
// `./NAME.js`, with their `NAME.d.ts` types. Further arguments are modules those import (copied
// into pkg/ beside them, e.g. www/lib/viewport.js): shipped, not exported. The names after
// --modules are the further wasm-bindgen modules (ksmcmc_extras, ksmcmc_tabletop), exported as
// `./NAME.js` with their `NAME_bg.wasm`, beside the main one named after the crate.

import { existsSync, readdirSync, readFileSync } from 'node:fs';
import { basename, join } from 'node:path';

const cargo = readFileSync(process.argv[2] ?? 'Cargo.toml', 'utf8');
const pkgSection = cargo.split(/^\[/m).find((s) => s.startsWith('package]'));
if (!pkgSection) throw new Error('Cargo.toml has no [package] section');
const field = (key) => {
  const m = new RegExp(`^${key}\\s*=\\s*"([^"]*)"`, 'm').exec(pkgSection);
  if (!m) throw new Error(`Cargo.toml [package] has no ${key}`);
  return m[1];
};
const list = (key) => {
  const m = new RegExp(`^${key}\\s*=\\s*\\[([^\\]]*)\\]`, 'm').exec(pkgSection);
  return m ? [...m[1].matchAll(/"([^"]*)"/g)].map((x) => x[1]) : [];
};

const name = field('name');
const npmDir = process.argv[3] ?? 'npm';
const extras = existsSync(npmDir) ? readdirSync(npmDir).filter((f) => f.endsWith('.js')).sort() : [];
for (const f of extras) {
  if (!existsSync(join(npmDir, f.replace(/\.js$/, '.d.ts')))) throw new Error(`${npmDir}/${f} has no .d.ts beside it`);
}
const rest = process.argv.slice(4);
const cut = rest.includes('--modules') ? rest.indexOf('--modules') : rest.length;
const internal = rest.slice(0, cut).map((p) => basename(p));
const modules = rest.slice(cut + 1);
for (const f of internal) {
  if (!f.endsWith('.js') || extras.includes(f)) throw new Error(`${f}: an imported module must be a .js file not in ${npmDir}`);
}
const json = {
  name,
  version: field('version'),
  description: field('description'),
  license: field('license'),
  keywords: list('keywords'),
  type: 'module',
  main: `${name}.js`,
  module: `${name}.js`,
  types: `${name}.d.ts`,
  exports: {
    '.': { types: `./${name}.d.ts`, default: `./${name}.js` },
    [`./${name}_bg.wasm`]: `./${name}_bg.wasm`,
    ...Object.fromEntries(
      modules.flatMap((m) => [
        [`./${m}.js`, { types: `./${m}.d.ts`, default: `./${m}.js` }],
        [`./${m}_bg.wasm`, `./${m}_bg.wasm`],
      ]),
    ),
    ...Object.fromEntries(
      extras.map((f) => [`./${f}`, { types: `./${f.replace(/\.js$/, '.d.ts')}`, default: `./${f}` }]),
    ),
  },
  files: [
    ...[name, ...modules].flatMap((m) => [`${m}_bg.wasm`, `${m}.js`, `${m}.d.ts`, `${m}_bg.wasm.d.ts`]),
    ...extras.flatMap((f) => [f, f.replace(/\.js$/, '.d.ts')]),
    ...internal,
    'README.md',
  ],
  sideEffects: ['./snippets/*'],
};
process.stdout.write(`${JSON.stringify(json, null, 2)}\n`);
