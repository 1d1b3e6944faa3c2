#!/usr/bin/env node
// Time to a settled plan on the live mapper page, as a reader meets it: open a map file (which
// turns Stop when settled on), press Start, and wait until the page stops because the best
// world has settled, then until it shows that world's plan (its rooms, and for a building of
// wings the wings' chains run). Beside it, in the same run, `ksmcmc floorplan MAP --seed 1`
// (the CLI's default) is timed, and its plan and the page's (the CLI's at the iterations the
// page ran: the same bytes) scored against the map's truth where there is one
// (`NAME_gt_segmentation.png` beside it). Prints, per map, the seconds from Start to the stop
// and to the plan, the native seconds and their ratio, the iteration it settled at, the
// window, units, doors and rooms of the best world, and precision / recall of both.
//
//   node scripts/settle-time.mjs [--datasets DIR] [--timeout SECONDS] [MAP ...]
//
// MAP defaults to the Radish Cartesium map and the Bormann et al. office_e and lab_a maps in
// ../shared/datasets. Needs www/pkg (make www-pkg), the release CLI (make cli), Debian's
// chromium and tests/e2e's playwright-core (make e2e-deps). Figures, not a test: they depend on
// the machine and its load.

import { execFileSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { createRequire } from 'node:module';
import { cpus, loadavg, tmpdir } from 'node:os';
import { basename, dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const REPO = resolve(dirname(fileURLToPath(import.meta.url)), '..');
const require = createRequire(join(REPO, 'tests/e2e/package.json'));
const { chromium } = require('playwright-core');
const { serve } = await import(join(REPO, 'tests/e2e/server.mjs'));

function parseArgs(argv) {
  const args = { datasets: resolve(REPO, '../shared/datasets'), timeout: 900, maps: [] };
  for (let i = 0; i < argv.length; i++) {
    const key = argv[i];
    if (key === '--datasets') args.datasets = resolve(argv[++i]);
    else if (key === '--timeout') args.timeout = Number(argv[++i]);
    else if (key === '--help' || key === '-h') {
      console.log('usage: node scripts/settle-time.mjs [--datasets DIR] [--timeout SECONDS] [MAP ...]');
      process.exit(0);
    } else if (key.startsWith('--')) throw new Error(`unknown argument ${key}; see --help`);
    else args.maps.push(resolve(key));
  }
  if (!(args.timeout > 0)) throw new Error('--timeout: a number of seconds above 0');
  if (!args.maps.length) {
    args.maps = ['radish/ubremen-cartesium.png', 'bormann2016/office_e.png', 'bormann2016/lab_a_scan.png'].map((p) => join(args.datasets, p));
  }
  return args;
}

/** Opens `map` on the mapper page, presses Start and waits for the settled stop. */
async function settle(browser, url, map, timeoutS) {
  const context = await browser.newContext({ viewport: { width: 1280, height: 900 } });
  const page = await context.newPage();
  try {
    await page.goto(`${url}mapper.html`);
    await page.waitForFunction(() => document.documentElement.dataset.state === 'ready', null, { timeout: 60_000 });
    await page.setInputFiles('#file', map);
    await page.waitForFunction((name) => document.getElementById('map-name').textContent.includes(name), basename(map), { timeout: 60_000 });
    if (!(await page.isChecked('#stop-settled'))) throw new Error('Stop when settled is not on for an opened map');
    const setup = await page.evaluate(() => window.__ksmcmc.snapshot());
    await page.evaluate(() => document.activeElement?.blur());
    const t0 = Date.now();
    await page.keyboard.press('Space');
    await page.waitForFunction(() => document.documentElement.dataset.running === 'true');
    await page.waitForFunction(
      () => document.documentElement.dataset.running === 'false' && window.__ksmcmc.snapshot().settledAt !== null,
      null,
      { timeout: timeoutS * 1000, polling: 100 },
    );
    const seconds = (Date.now() - t0) / 1000;
    await page.evaluate(() => window.__ksmcmc.idle());
    const planSeconds = (Date.now() - t0) / 1000;
    const s = await page.evaluate(() => window.__ksmcmc.snapshot());
    const report = JSON.parse(await page.evaluate(() => window.__ksmcmc.mapper.reportJson()));
    return { map: basename(map), width: setup.width, height: setup.height, seconds, planSeconds, settledAt: s.settledAt, iterations: s.iteration, window: s.settleWindow, units: report.units, doors: report.doors, rooms: report.rooms };
  } finally {
    await context.close();
  }
}

const CLI = join(REPO, 'target/release/ksmcmc');

/**
 * `ksmcmc floorplan map --seed 1` (with `--iterations n` if given): wall seconds, and
 * precision / recall against `truth` if there is one.
 */
function native(map, truth, n) {
  const out = mkdtempSync(join(tmpdir(), 'settle-'));
  try {
    const t0 = Date.now();
    execFileSync(CLI, ['floorplan', map, '--seed', '1', '--out', out, ...(n ? ['--iterations', String(n)] : [])], { stdio: 'ignore' });
    const seconds = (Date.now() - t0) / 1000;
    const report = JSON.parse(readFileSync(join(out, 'report.json'), 'utf8'));
    let score = null;
    if (truth) score = JSON.parse(execFileSync(CLI, ['score', join(out, 'labels.pgm'), truth, '--json'], { encoding: 'utf8' }));
    return { seconds, k: report.cell_prediction_rate, score };
  } finally {
    rmSync(out, { recursive: true, force: true });
  }
}

const args = parseArgs(process.argv.slice(2));
if (!existsSync(CLI)) throw new Error(`${CLI} is missing: make cli`);
if (!existsSync(join(REPO, 'www/pkg/ksmcmc_bg.wasm'))) throw new Error('www/pkg is missing: make www-pkg');
const server = await serve(join(REPO, 'www'));
const browser = await chromium.launch({ executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium', args: ['--no-sandbox', '--disable-gpu', '--disable-dev-shm-usage'] });
try {
  console.log(`${cpus().length} x ${cpus()[0]?.model ?? 'CPU'}, load average ${loadavg().map((l) => l.toFixed(1)).join(' ')}`);
  console.log('| map | cells | page: seconds to settled | to the plan | native default, s | page / native | settled at | window | units | doors | rooms | K page / native | precision / recall page | native |');
  console.log('|---|---|---|---|---|---|---|---|---|---|---|---|---|---|');
  for (const map of args.maps) {
    if (!existsSync(map)) {
      console.log(`| ${basename(map)} | absent | | | | | | | | | | | | |`);
      continue;
    }
    const r = await settle(browser, server.url, map, args.timeout);
    const n = (v) => Number(v).toLocaleString('en-US');
    const truth = map.replace(/(_furnitures)?\.png$/, '_gt_segmentation.png');
    const hasTruth = truth !== map && existsSync(truth);
    const cli = native(map, hasTruth ? truth : null);
    const same = native(map, hasTruth ? truth : null, r.iterations);
    const pr = (x) => (x.score ? `${x.score.precision.toFixed(3)} / ${x.score.recall.toFixed(3)}` : '–');
    console.log(
      `| ${r.map} | ${r.width}x${r.height} | ${r.seconds.toFixed(1)} | ${r.planSeconds.toFixed(1)} | ${cli.seconds.toFixed(1)} | ${(r.planSeconds / cli.seconds).toFixed(1)} | ` +
        `${n(r.settledAt)} | ${n(r.window)} | ${r.units} | ${r.doors} | ${r.rooms} | ${same.k.toFixed(4)} / ${cli.k.toFixed(4)} | ${pr(same)} | ${pr(cli)} |`,
    );
  }
  console.log(`load average after: ${loadavg().map((l) => l.toFixed(1)).join(' ')}`);
} finally {
  await browser.close();
  await server.close();
}
