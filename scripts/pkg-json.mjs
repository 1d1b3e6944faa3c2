#!/usr/bin/env node
// Writes pkg/package.json for the npm package that wasm-bindgen generated into pkg/.
// Usage: node scripts/pkg-json.mjs [Cargo.toml] > pkg/package.json
// Name, version, description and licence come from Cargo.toml's [package] section, so the
// npm package and the crate never disagree.

import { readFileSync } from 'node:fs';

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
  },
  files: [`${name}_bg.wasm`, `${name}.js`, `${name}.d.ts`, `${name}_bg.wasm.d.ts`, 'README.md'],
  sideEffects: ['./snippets/*'],
};
process.stdout.write(`${JSON.stringify(json, null, 2)}\n`);
