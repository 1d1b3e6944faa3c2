// Small line plots of a chain's trace, and the parsing of the mapper page's number inputs.
// The geometry is pure (testable without a browser); `drawPlot` paints it on a 2D canvas.

/**
 * The y range to plot `ys` in: their minimum and maximum, widened by 5 % (or by 1 when all are
 * equal) so the line never sits on the frame. Non-finite values are ignored.
 * @param {ArrayLike<number>} ys
 * @param {[number, number] | null} fixed a fixed range, e.g. [0, 1] for a rate
 * @returns {[number, number]}
 */
export function yRange(ys, fixed = null) {
  if (fixed) return fixed;
  let lo = Infinity;
  let hi = -Infinity;
  for (let i = 0; i < ys.length; i++) {
    const y = ys[i];
    if (Number.isFinite(y)) {
      if (y < lo) lo = y;
      if (y > hi) hi = y;
    }
  }
  if (lo === Infinity) return [0, 1];
  if (lo === hi) return [lo - 1, hi + 1];
  const pad = (hi - lo) * 0.05;
  return [lo - pad, hi + pad];
}

/**
 * Pixel positions of the points (xs[i], ys[i]) in a `width` x `height` box with `pad` pixels
 * of margin, x growing right and y up. At most about two points per pixel column are kept
 * (every k-th point, and always the last), so a long trace plots as fast as a short one.
 * @returns {Array<[number, number]>}
 */
export function plotPoints(xs, ys, width, height, { pad = 4, range = null } = {}) {
  const n = Math.min(xs.length, ys.length);
  if (n === 0 || width <= 2 * pad || height <= 2 * pad) return [];
  const [lo, hi] = yRange(ys, range);
  const x0 = xs[0];
  const x1 = xs[n - 1];
  const spanX = x1 > x0 ? x1 - x0 : 1;
  const w = width - 2 * pad;
  const h = height - 2 * pad;
  const stride = Math.max(1, Math.floor(n / (2 * w)));
  const out = [];
  for (let i = 0; i < n; i += stride) {
    if (i + stride >= n) i = n - 1;
    const y = Number.isFinite(ys[i]) ? ys[i] : lo;
    const px = n === 1 ? pad + w : pad + ((xs[i] - x0) / spanX) * w;
    const py = pad + h - ((Math.min(hi, Math.max(lo, y)) - lo) / (hi - lo)) * h;
    out.push([px, py]);
  }
  return out;
}

/** Elements' client sizes (clientWidth, clientHeight) as their ResizeObserver last saw them. */
const sizes = new WeakMap();
let observer = null;

/**
 * `el`'s clientWidth and clientHeight, without laying out the page: read once
 * (the first call may lay it out), then kept up to date by a ResizeObserver. A plot drawn every
 * frame after the page's text changed would otherwise lay out the whole page in the frame's
 * script, a second time before the frame's own layout (8 - 15 ms on a busy machine).
 * @param {Element} el
 * @returns {{width: number, height: number}}
 */
export function cssSize(el) {
  let size = sizes.get(el);
  if (!size) {
    size = { width: el.clientWidth, height: el.clientHeight };
    sizes.set(el, size);
    if (typeof ResizeObserver === 'function') {
      observer ??= new ResizeObserver((entries) => {
        for (const e of entries) {
          const s = sizes.get(e.target);
          // Read in the observer's callback, after layout: no layout of its own.
          if (s) {
            s.width = e.target.clientWidth;
            s.height = e.target.clientHeight;
          }
        }
      });
      observer.observe(el);
    } else {
      sizes.delete(el);
    }
  }
  return size;
}

/**
 * Draws a line plot on a canvas, sized to its CSS box times the device pixel ratio.
 * @param {HTMLCanvasElement} canvas
 * @param {ArrayLike<number>} xs
 * @param {ArrayLike<number>} ys
 * @param {{color?: string, range?: [number, number] | null, grid?: string}} style
 */
export function drawPlot(canvas, xs, ys, { color = '#1f5fbf', range = null, grid = 'rgba(128,128,128,.35)' } = {}) {
  const dpr = globalThis.devicePixelRatio || 1;
  const box = cssSize(canvas);
  const width = Math.max(40, Math.round((box.width || canvas.width) * dpr));
  const height = Math.max(30, Math.round((box.height || canvas.height) * dpr));
  if (canvas.width !== width || canvas.height !== height) {
    canvas.width = width;
    canvas.height = height;
  }
  const ctx = canvas.getContext('2d');
  ctx.clearRect(0, 0, width, height);
  const pad = 4 * dpr;
  ctx.strokeStyle = grid;
  ctx.lineWidth = 1;
  ctx.strokeRect(pad - 0.5, pad - 0.5, width - 2 * pad + 1, height - 2 * pad + 1);
  const pts = plotPoints(xs, ys, width, height, { pad, range });
  if (pts.length === 0) return;
  ctx.strokeStyle = color;
  ctx.lineWidth = 1.5 * dpr;
  ctx.lineJoin = 'round';
  ctx.beginPath();
  ctx.moveTo(pts[0][0], pts[0][1]);
  for (const [x, y] of pts.slice(1)) ctx.lineTo(x, y);
  if (pts.length === 1) ctx.lineTo(pts[0][0] - 2, pts[0][1]);
  ctx.stroke();
}

/** The largest number of iterations per frame the page accepts. */
export const MAX_ITERATIONS_PER_FRAME = 100000;

/**
 * Reads the "iterations per frame" field: `auto` (or empty) for a time budget per frame, or a
 * whole number from 1 to 100000.
 * @param {string} text
 * @returns {'auto' | number}
 */
export function parseIterationsPerFrame(text) {
  const t = String(text).trim().toLowerCase();
  if (t === '' || t === 'auto') return 'auto';
  if (!/^\d+$/.test(t) || Number(t) < 1 || Number(t) > MAX_ITERATIONS_PER_FRAME) {
    throw new Error(
      `Iterations per frame: "${String(text).trim()}" is not allowed; enter auto, or a whole number from 1 to ${MAX_ITERATIONS_PER_FRAME}.`,
    );
  }
  return Number(t);
}

/**
 * The number formats by decimals, made once: `toLocaleString` with options builds a new format
 * at every call, and the first one loads the locale's data, a task of 20 - 30 ms that fell on
 * the first frame after Start. The common ones are made when the page loads.
 * @type {Intl.NumberFormat[]}
 */
const FORMATS = [];

function numberFormat(decimals) {
  FORMATS[decimals] ??= new Intl.NumberFormat('en-US', { minimumFractionDigits: decimals, maximumFractionDigits: decimals });
  return FORMATS[decimals];
}
for (const decimals of [0, 1, 4]) numberFormat(decimals);

/** A number for the statistics list: grouped digits, a fixed number of decimals. */
export function formatNumber(x, decimals = 0) {
  if (!Number.isFinite(x)) return '–';
  return numberFormat(decimals).format(x);
}
