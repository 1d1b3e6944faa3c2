// Prior shaping (Liu 2014, Fig. 2.2): a one-dimensional likelihood with three optima, a prior
// from a small Markov logic network over the region x falls in, and their product, the
// posterior, which a Metropolis random walk samples frame by frame. The prior's numbers come
// from the library's MLN engine (mlnLogWeight); this file is wiring and drawing.

import init, { checkRules, mlnLogWeight } from './pkg/ksmcmc_rules.js';
import { messages } from './lib/messages.js';
import { rulesEditor } from './lib/rules-editor.js';

const N = 400; // grid points over [0, 10]
const XMAX = 10;
const BINS = 50;
const REGIONS = ['Left', 'Middle', 'Right'];
const STEPS_PER_FRAME = 300;
// The likelihood: three Gaussians, the middle optimum slightly the highest.
const MODES = [
  { mu: 2, sigma: 0.6, w: 0.9 },
  { mu: 5, sigma: 0.6, w: 1.0 },
  { mu: 8, sigma: 0.6, w: 0.9 },
];

const DEFAULT_KB = `// Which region x is in: exactly one of three.
Left(pt)
Middle(pt)
Right(pt)
Left(x) => !Middle(x) ^ !Right(x).
Middle(x) => !Right(x).

// Knowledge: the weight of each region (the sliders edit these lines).
0 Left(x)
0 Middle(x)
0 Right(x)
`;

const $ = (id) => document.getElementById(id);
const { showError } = messages({ message: $('message'), messageText: $('message-text'), messageClose: $('message-close') });
const ui = { kb: $('kb'), error: $('kb-error'), plot: $('plot'), mass: $('mass'), samples: $('samples'), acceptance: $('acceptance') };

const state = {
  editor: null,
  goodKb: DEFAULT_KB,
  error: null,
  logWeights: [0, 0, 0],
  xs: Array.from({ length: N }, (_, i) => ((i + 0.5) * XMAX) / N),
  likelihood: [],
  prior: [],
  posterior: [],
  mass: [0, 0, 0],
  hist: new Array(BINS).fill(0),
  samples: 0,
  accepted: 0,
  x: 5,
  seed: 12345,
  version: 0,
};

const region = (x) => (x < XMAX / 3 ? 0 : x < (2 * XMAX) / 3 ? 1 : 2);
const gauss = (x, m) => (m.w * Math.exp(-((x - m.mu) ** 2) / (2 * m.sigma ** 2))) / m.sigma;
state.likelihood = state.xs.map((x) => MODES.reduce((s, m) => s + gauss(x, m), 0));
{
  const z = state.likelihood.reduce((a, b) => a + b, 0) * (XMAX / N);
  state.likelihood = state.likelihood.map((v) => v / z);
}

// A small deterministic generator (mulberry32), so that runs are repeatable.
function random() {
  let t = (state.seed = (state.seed + 0x6d2b79f5) | 0);
  t = Math.imul(t ^ (t >>> 15), t | 1);
  t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
  return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
}
function normal() {
  const u = 1 - random();
  return Math.sqrt(-2 * Math.log(u)) * Math.cos(2 * Math.PI * random());
}

/** Line of a region's weight in the knowledge base: `<number> Region(x)`. */
const weightLine = (r) => new RegExp(`^(\\s*)(-?[0-9.eE+-]+)(\\s+${r}\\(x\\)\\s*(//.*)?)$`, 'm');

/**
 * The editor's check: the text must parse and give every region a log weight. On success it
 * becomes the knowledge base; on error the last good one stays.
 */
function checkKb(text) {
  const err = checkRules(text);
  if (err) return err;
  let lw;
  try {
    lw = REGIONS.map((r) => mlnLogWeight(text, `${r}(X)`));
  } catch (e) {
    return { line: 0, column: 0, message: String(e.message ?? e) };
  }
  state.goodKb = text;
  state.logWeights = lw;
  recompute();
  return null;
}

function applyKb(text, err) {
  state.error = err;
  syncSliders(text);
}

function syncSliders(text) {
  for (const r of REGIONS) {
    const m = text.match(weightLine(r));
    const input = $(`w-${r}`);
    input.disabled = !m;
    if (m && document.activeElement !== input) input.value = Number(m[2]);
    $(`o-${r}`).textContent = m ? Number(m[2]).toFixed(1) : '–';
  }
}

function recompute() {
  const finite = state.logWeights.map((w) => (Number.isFinite(w) ? w : -Infinity));
  const top = Math.max(...finite.filter(Number.isFinite), 0);
  const pr = state.xs.map((x) => Math.exp(finite[region(x)] - top));
  const dx = XMAX / N;
  const zp = pr.reduce((a, b) => a + b, 0) * dx || 1;
  state.prior = pr.map((v) => v / zp);
  const post = state.prior.map((p, i) => p * state.likelihood[i]);
  const z = post.reduce((a, b) => a + b, 0) * dx || 1;
  state.posterior = post.map((v) => v / z);
  state.mass = [0, 0, 0];
  state.xs.forEach((x, i) => (state.mass[region(x)] += state.posterior[i] * dx));
  state.version++;
  restartSampler();
}

function restartSampler() {
  state.hist.fill(0);
  state.samples = 0;
  state.accepted = 0;
  state.x = 5;
}

const density = (x) => (x < 0 || x >= XMAX ? 0 : state.posterior[Math.min(N - 1, Math.floor((x / XMAX) * N))]);

function sample(n) {
  let p = density(state.x);
  for (let i = 0; i < n; i++) {
    const y = state.x + 1.5 * normal();
    const q = density(y);
    if (q > 0 && (p === 0 || random() < q / p)) {
      state.x = y;
      p = q;
      state.accepted++;
    }
    state.hist[Math.min(BINS - 1, Math.floor((state.x / XMAX) * BINS))]++;
    state.samples++;
  }
}

function draw() {
  const c = ui.plot;
  const g = c.getContext('2d');
  const W = c.width;
  const H = c.height;
  const pad = 24;
  g.fillStyle = '#fff';
  g.fillRect(0, 0, W, H);
  const ymax = Math.max(...state.posterior, ...state.likelihood, ...state.prior) * 1.1 || 1;
  const X = (x) => pad + ((W - 2 * pad) * x) / XMAX;
  const Y = (y) => H - pad - ((H - 2 * pad) * y) / ymax;
  // histogram, scaled to a density
  if (state.samples > 0) {
    g.fillStyle = '#ccc';
    const bw = XMAX / BINS;
    state.hist.forEach((h, b) => {
      const d = h / state.samples / bw;
      g.fillRect(X(b * bw) + 1, Y(d), X(bw) - X(0) - 2, Y(0) - Y(d));
    });
  }
  // region borders
  g.strokeStyle = '#ddd';
  g.setLineDash([4, 4]);
  for (const b of [XMAX / 3, (2 * XMAX) / 3]) {
    g.beginPath();
    g.moveTo(X(b), pad);
    g.lineTo(X(b), H - pad);
    g.stroke();
  }
  g.setLineDash([]);
  g.strokeStyle = '#000';
  g.beginPath();
  g.moveTo(pad, H - pad);
  g.lineTo(W - pad, H - pad);
  g.stroke();
  g.fillStyle = '#000';
  g.font = '12px sans-serif';
  for (let t = 0; t <= XMAX; t += 2) g.fillText(String(t), X(t) - 3, H - 6);
  // The likelihood wide and solid, the posterior narrow and dashed on top: where the prior is
  // flat the two are the same curve, and both stay visible.
  const curve = (ys, color, width, dash) => {
    g.strokeStyle = color;
    g.lineWidth = width;
    g.setLineDash(dash);
    g.beginPath();
    ys.forEach((y, i) => (i ? g.lineTo(X(state.xs[i]), Y(y)) : g.moveTo(X(state.xs[i]), Y(y))));
    g.stroke();
    g.setLineDash([]);
    g.lineWidth = 1;
  };
  curve(state.likelihood, '#1f77b4', 5, []);
  curve(state.prior, '#2ca02c', 2, []);
  curve(state.posterior, '#d62728', 2, [8, 5]);
  ui.mass.textContent = state.mass.map((m) => m.toFixed(3)).join(' / ');
  ui.samples.textContent = String(state.samples);
  ui.acceptance.textContent = state.samples ? (state.accepted / state.samples).toFixed(2) : '–';
}

function frame() {
  if (state.samples < 2_000_000) sample(STEPS_PER_FRAME);
  draw();
  requestAnimationFrame(frame);
}

function onSlider(r) {
  const input = $(`w-${r}`);
  const text = ui.kb.value;
  const re = weightLine(r);
  if (!re.test(text)) return;
  ui.kb.value = text.replace(re, (_, a, _w, rest) => `${a}${Number(input.value)}${rest}`);
  state.editor.check();
}

async function main() {
  try {
    await init();
    ui.kb.value = DEFAULT_KB;
    state.editor = rulesEditor(ui.kb, { check: checkKb, status: ui.error, okText: 'Knowledge base OK', gutterId: 'gutter', onCheck: applyKb });
    for (const r of REGIONS) $(`w-${r}`).addEventListener('input', () => onSlider(r));
    $('restart').addEventListener('click', restartSampler);
    window.__prior = {
      snapshot: () => ({
        error: state.error,
        goodKb: state.goodKb,
        logWeights: state.logWeights,
        mass: state.mass,
        samples: state.samples,
        hist: [...state.hist],
        histMass: REGIONS.map((_, k) => state.hist.reduce((s, h, b) => s + (Math.floor((b * 3) / BINS) === k ? h : 0), 0) / Math.max(1, state.samples)),
        version: state.version,
      }),
    };
    document.documentElement.dataset.state = 'ready';
    requestAnimationFrame(frame);
  } catch (e) {
    document.documentElement.dataset.state = 'error';
    showError(e);
  }
}
main();
