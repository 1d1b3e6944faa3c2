#!/usr/bin/env node
// The floor-plan chain's speed in WebAssembly, in headless Chromium: the maps and settings of
// the native `ksmcmc bench` (the Radish Cartesium map from ../shared/datasets and synthetic
// 556x322 and 1237x672 maps, seed 7; 20000 iterations with chain seed 1), so the two tables
// compare row by row. Prints iterations per second, the setup time (orientation, detectors),
// the best log posterior and K(W,M), which equal the native ones (same seed, same result).
//
//   node scripts/bench-wasm.mjs [--iterations N] [--seed S] [--datasets DIR] [--native BIN]
//
// --native BIN also runs `BIN bench` with the same arguments and prints wasm/native ratios.
// Needs www/pkg (make www-pkg), Debian's chromium and tests/e2e's playwright-core (make
// e2e-deps); `make bench-wasm` does all that. Speed, not a test: numbers depend on the machine.

import { spawnSync } from 'node:child_process';
import { existsSync, readFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { cpus } from 'node:os';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const REPO = resolve(dirname(fileURLToPath(import.meta.url)), '..');
const require = createRequire(join(REPO, 'tests/e2e/package.json'));
const { chromium } = require('playwright-core');
const { serve } = await import(join(REPO, 'tests/e2e/server.mjs'));

function parseArgs(argv) {
  const args = { iterations: 20000, seed: 1, datasets: resolve(REPO, '../shared/datasets'), native: null };
  for (let i = 0; i < argv.length; i++) {
    const [key, value] = [argv[i], argv[i + 1]];
    if (key === '--iterations' || key === '--seed') {
      const n = Number(value);
      if (!Number.isSafeInteger(n) || n < (key === '--seed' ? 0 : 1)) throw new Error(`${key}: ${value} is not a whole number`);
      args[key.slice(2)] = n;
    } else if (key === '--datasets') args.datasets = resolve(value);
    else if (key === '--native') args.native = resolve(value);
    else if (key === '--help' || key === '-h') {
      console.log('usage: node scripts/bench-wasm.mjs [--iterations N] [--seed S] [--datasets DIR] [--native BIN]');
      process.exit(0);
    } else throw new Error(`unknown argument ${key}; see --help`);
    i++;
  }
  return args;
}

/** Runs in the page: the same loop as `ksmcmc bench`'s run_one. */
async function benchInPage({ maps, iterations, seed }) {
  const m = await import('/pkg/ksmcmc.js');
  const sy = await import('/pkg/ksmcmc_synth.js');
  await Promise.all([m.default(), sy.default()]);
  const rows = [];
  for (const spec of maps) {
    let map;
    if (spec.b64) {
      const bytes = Uint8Array.from(atob(spec.b64), (c) => c.charCodeAt(0));
      map = m.Map.fromBytes(bytes);
    } else {
      const s = sy.synth(spec.synthSeed, JSON.stringify({ width: spec.width, height: spec.height }));
      map = m.Map.fromYaml(s.mapYaml, s.mapPgm);
      s.free();
    }
    const t0 = performance.now();
    const mapper = new m.Mapper(map, undefined, seed);
    const setup = performance.now() - t0;
    const start = mapper.logPosterior;
    const t1 = performance.now();
    const marks = [];
    while (mapper.iteration < iterations) {
      mapper.step(Math.min(250, iterations - mapper.iteration));
      marks.push([mapper.iteration, performance.now() - t1, mapper.bestLogPosterior]);
    }
    const ms = performance.now() - t1;
    const best = mapper.bestLogPosterior;
    const target = best - 0.001 * Math.abs(best - start);
    const hit = marks.find((x) => x[2] >= target) ?? [iterations, ms];
    rows.push({
      name: spec.name,
      cells: [map.width, map.height],
      setup: setup / 1000,
      seconds: ms / 1000,
      iterations: mapper.iteration,
      convergedAt: hit[0],
      convergedS: hit[1] / 1000,
      best,
      k: mapper.bestPredictionRate,
    });
    mapper.free();
    map.free();
  }
  return { rows, userAgent: navigator.userAgent };
}

function table(rows) {
  const lines = [
    '| map | cells | setup s | iterations | seconds | iterations/s | converged (it / s) | log posterior | K(W,M) |',
    '|---|---|---|---|---|---|---|---|---|',
  ];
  for (const r of rows) {
    lines.push(
      `| ${r.name} | ${r.cells[0]}x${r.cells[1]} | ${r.setup.toFixed(3)} | ${r.iterations} | ${r.seconds.toFixed(2)} | ` +
        `${Math.round(r.iterations / Math.max(r.seconds, 1e-9))} | ${r.convergedAt} / ${r.convergedS.toFixed(2)} | ` +
        `${r.best.toFixed(1)} | ${r.k.toFixed(4)} |`,
    );
  }
  return lines.join('\n');
}

/** Rows of the native `ksmcmc bench` table: name, setup s, iterations/s, K. */
function nativeRows(text) {
  const rows = new Map();
  for (const line of text.split('\n')) {
    const c = line.split('|').map((x) => x.trim());
    if (c.length < 9 || !/^\d+x\d+$/.test(c[2])) continue;
    rows.set(c[1], { setup: Number(c[3]), perSecond: Number(c[6]), k: Number(c[8]) });
  }
  return rows;
}

async function main() {
  const args = parseArgs(process.argv.slice(2));
  const chromiumPath = process.env.CHROMIUM ?? '/usr/bin/chromium';
  const www = join(REPO, 'www');
  if (!existsSync(join(www, 'pkg/ksmcmc_bg.wasm'))) throw new Error('www/pkg is missing: run `make www-pkg`');
  const maps = [];
  const radish = join(args.datasets, 'radish/ubremen-cartesium.png');
  if (existsSync(radish)) {
    maps.push({ name: 'ubremen-cartesium (Radish)', b64: readFileSync(radish).toString('base64') });
  } else {
    console.error(`bench-wasm: ${radish} not found; skipping the Cartesium map`);
  }
  for (const [width, height] of [[556, 322], [1237, 672]]) {
    maps.push({ name: `synthetic ${width}x${height} (seed 7)`, synthSeed: 7, width, height });
  }

  const server = await serve(www);
  const browser = await chromium.launch({
    executablePath: chromiumPath,
    args: ['--no-sandbox', '--disable-gpu', '--disable-dev-shm-usage', '--no-first-run'],
  });
  let result;
  try {
    const page = await browser.newPage();
    await page.goto(`${server.url}index.html`);
    result = await page.evaluate(benchInPage, { maps, iterations: args.iterations, seed: args.seed });
  } finally {
    await browser.close();
    await server.close();
  }
  console.log(`WebAssembly in headless ${result.userAgent.match(/(Headless)?Chrome\/[\d.]+/)?.[0] ?? 'Chromium'}, ` +
    `${cpus()[0]?.model ?? 'unknown CPU'} x ${cpus().length}; ${args.iterations} iterations, chain seed ${args.seed}`);
  console.log(table(result.rows));

  if (args.native) {
    const run = spawnSync(args.native, ['bench', '--iterations', String(args.iterations), '--seed', String(args.seed), '--datasets', args.datasets], { encoding: 'utf8' });
    if (run.status !== 0) throw new Error(`${args.native} bench failed: ${run.stderr}`);
    console.log(`\nnative (${args.native} bench):`);
    console.log(run.stdout.trim());
    const native = nativeRows(run.stdout);
    console.log('\n| map | wasm iterations/s | native iterations/s | native / wasm | wasm setup s | native setup s | same K |');
    console.log('|---|---|---|---|---|---|---|');
    for (const r of result.rows) {
      const n = native.get(r.name);
      if (!n) continue;
      const perSecond = r.iterations / r.seconds;
      console.log(
        `| ${r.name} | ${Math.round(perSecond)} | ${n.perSecond} | ${(n.perSecond / perSecond).toFixed(2)}x | ` +
          `${r.setup.toFixed(3)} | ${n.setup.toFixed(3)} | ${r.k.toFixed(4) === n.k.toFixed(4) ? 'yes' : `no (${n.k})`} |`,
      );
    }
  }
}

main().catch((err) => {
  console.error(`bench-wasm: ${err.message}`);
  process.exit(1);
});
