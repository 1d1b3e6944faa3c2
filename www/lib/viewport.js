// Zoom and pan for a picture shown on a canvas: wheel, pinch, drag, keyboard and buttons.
//
// The live mapper, the table-top page and the `mount` embed all show a picture (an
// ImageBitmap or a canvas drawn by the library) scaled to fit a canvas. A floor plan of a
// building is too dense to read at that size, so each of them lets the reader zoom in and
// move around. This module is the one place that does it: a `View` (pure arithmetic: a zoom
// and the content point at the centre, clamped so that the picture always fills the canvas)
// and a `Viewport` that binds a View to a canvas's events and draws pictures through it.
//
// Coordinates: "content" positions are fractions of the picture, (0, 0) top left to (1, 1)
// bottom right, whatever its size in pixels; "element" positions are fractions of the canvas
// as shown. At zoom 1 they are the same. Content stays put under the cursor when zooming by
// wheel or pinch, and keyboard and button zooms keep the centre.
//
// No dependencies; the published package ships it beside mount.js.

/** Zoom limits: 1 is the whole picture. */
export const MIN_ZOOM = 1;
export const MAX_ZOOM = 16;
/** Zoom factor of one key press or button press. */
export const ZOOM_STEP = 1.5;
/** Share of the canvas an arrow key moves the view (with Shift: half the canvas). */
export const PAN_STEP = 0.125;
/** CSS pixels a pointer must move before a press becomes a drag (otherwise it is a tap). */
export const TAP_SLOP = 4;

const clamp = (v, lo, hi) => Math.min(hi, Math.max(lo, v));

/** A zoom and a centre, in content fractions, always showing only the picture. */
export class View {
  /** @param {{ maxZoom?: number }} [options] */
  constructor({ maxZoom = MAX_ZOOM } = {}) {
    this.maxZoom = Math.max(MIN_ZOOM, maxZoom);
    this.reset();
  }

  /** The whole picture. */
  reset() {
    this.zoom = MIN_ZOOM;
    this.cx = 0.5;
    this.cy = 0.5;
  }

  /** Whether the whole picture is shown. */
  get isReset() {
    return this.zoom === MIN_ZOOM;
  }

  /** Keeps the zoom in its limits and the view on the picture. */
  clamp() {
    this.zoom = clamp(Number.isFinite(this.zoom) ? this.zoom : MIN_ZOOM, MIN_ZOOM, this.maxZoom);
    const half = 0.5 / this.zoom;
    this.cx = clamp(Number.isFinite(this.cx) ? this.cx : 0.5, half, 1 - half);
    this.cy = clamp(Number.isFinite(this.cy) ? this.cy : 0.5, half, 1 - half);
  }

  /** The content point shown at element point (fx, fy). */
  toContent(fx, fy) {
    return [this.cx + (fx - 0.5) / this.zoom, this.cy + (fy - 0.5) / this.zoom];
  }

  /** Where content point (u, v) is shown, as element fractions (outside [0, 1]: off the canvas). */
  toElement(u, v) {
    return [(u - this.cx) * this.zoom + 0.5, (v - this.cy) * this.zoom + 0.5];
  }

  /**
   * Multiplies the zoom by `factor`, keeping the content under element point (fx, fy) there
   * (as far as the limits allow). Returns whether the view changed.
   */
  zoomAt(factor, fx = 0.5, fy = 0.5) {
    const [u, v] = this.toContent(fx, fy);
    return this.pinchTo(u, v, this.zoom * factor, fx, fy);
  }

  /**
   * Zoom `zoom` with content point (u, v) at element point (fx, fy) (as far as the limits
   * allow): where two fingers that started on (u, v) now are. Returns whether the view changed.
   */
  pinchTo(u, v, zoom, fx, fy) {
    const before = this.key();
    this.zoom = zoom;
    this.clamp();
    this.cx = u - (fx - 0.5) / this.zoom;
    this.cy = v - (fy - 0.5) / this.zoom;
    this.clamp();
    return this.key() !== before;
  }

  /** Moves the picture by (dfx, dfy) element fractions, as a drag does. Returns whether it moved. */
  panBy(dfx, dfy) {
    const before = this.key();
    this.cx -= dfx / this.zoom;
    this.cy -= dfy / this.zoom;
    this.clamp();
    return this.key() !== before;
  }

  /** Centres content point (u, v) (as far as the view allows) if it is not well inside the view. */
  reveal(u, v, margin = 0.1) {
    const [fx, fy] = this.toElement(u, v);
    if (fx >= margin && fx <= 1 - margin && fy >= margin && fy <= 1 - margin) return false;
    this.cx = u;
    this.cy = v;
    this.clamp();
    return true;
  }

  /**
   * The canvas transform that draws a picture of `sw` x `sh` pixels on a canvas of `tw` x `th`
   * pixels through this view: [a, b, c, d, e, f] for `setTransform`.
   */
  transform(tw, th, sw, sh) {
    const k = this.zoom;
    return [(k * tw) / sw, 0, 0, (k * th) / sh, tw * (0.5 - this.cx * k), th * (0.5 - this.cy * k)];
  }

  /** The view as plain numbers. */
  state() {
    return { zoom: this.zoom, cx: this.cx, cy: this.cy };
  }

  key() {
    return `${this.zoom},${this.cx},${this.cy}`;
  }
}

/**
 * Pixels per cell for a picture seen at `pxPerCell` device pixels per cell (at zoom 1) and
 * `zoom`: enough that it is not blown up, at most `maxScale`, and at most `maxPixels` pixels
 * for `cells` cells. At least 1.
 */
export function detailScale(pxPerCell, zoom, cells, { maxScale = 8, maxPixels = 8_000_000 } = {}) {
  const wanted = Math.ceil(pxPerCell * zoom - 0.01);
  const fits = Math.floor(Math.sqrt(maxPixels / Math.max(1, cells)));
  return Math.max(1, Math.min(maxScale, fits, Number.isFinite(wanted) ? wanted : 1));
}

/** The wheel's movement in CSS pixels, whatever unit the browser gave it in. */
function wheelPixels(e, height) {
  const unit = e.deltaMode === 1 ? 16 : e.deltaMode === 2 ? height : 1;
  return e.deltaY * unit;
}

/**
 * A View bound to a canvas (and to any other canvas shown the same way: `listen`): wheel
 * zooms about the cursor, two pointers pinch and pan, one pointer drags (when `dragPans()`),
 * and with the canvas focused + and − zoom, 0 resets and the arrow keys pan. `onChange` is
 * called after every change; `onTap(e, u, v)` for a press that did not move.
 */
export class Viewport {
  /**
   * @param {HTMLElement} element the canvas
   * @param {{ maxZoom?: number, onChange?: (view: View) => void, dragPans?: () => boolean,
   *   onTap?: (e: PointerEvent, u: number, v: number) => void, onPinch?: () => void,
   *   controls?: { className?: string, label?: string } | false }} [options]
   */
  constructor(element, options = {}) {
    this.element = element;
    this.view = new View(options);
    this.onChange = options.onChange ?? (() => {});
    this.dragPans = options.dragPans ?? (() => true);
    this.onTap = options.onTap ?? null;
    this.onPinch = options.onPinch ?? null;
    /** Pointers down on the canvas: id -> { x, y, el }. */
    this.pointers = new Map();
    this.gesture = null;
    this.listeners = [];
    this.listen(element);
    this.controls = options.controls === false ? null : this.makeControls(options.controls ?? {});
    this.update();
  }

  /** Zoom and pan on `el` too (another canvas showing the same picture, e.g. side by side). */
  listen(el) {
    const on = (type, fn, opts) => {
      el.addEventListener(type, fn, opts);
      this.listeners.push(() => el.removeEventListener(type, fn, opts));
    };
    on('wheel', (e) => this.wheel(e), { passive: false });
    on('pointerdown', (e) => this.down(e));
    on('pointermove', (e) => this.move(e));
    on('pointerup', (e) => this.up(e, true));
    on('pointercancel', (e) => this.up(e, false));
    on('keydown', (e) => this.key(e));
    el.style.touchAction = 'none';
  }

  /** Removes every listener and the controls. */
  destroy() {
    for (const off of this.listeners) off();
    this.listeners = [];
    this.controls?.remove();
  }

  /** Where a pointer event is, as element fractions of the canvas it happened on. */
  fractions(e, el = e.currentTarget ?? this.element) {
    return this.fractionsOf(e.clientX, e.clientY, el);
  }

  /** Client position (x, y) as element fractions of `el`. */
  fractionsOf(x, y, el = this.element) {
    const r = el.getBoundingClientRect();
    return [(x - r.left) / (r.width || 1), (y - r.top) / (r.height || 1)];
  }

  /** The content point (fractions of the picture) under a pointer event. */
  contentAt(e, el) {
    return this.view.toContent(...this.fractions(e, el));
  }

  changed() {
    this.update();
    this.onChange(this.view);
  }

  zoomBy(factor, fx = 0.5, fy = 0.5) {
    if (this.view.zoomAt(factor, fx, fy)) this.changed();
  }

  panBy(dfx, dfy) {
    if (this.view.panBy(dfx, dfy)) this.changed();
  }

  reset() {
    if (this.view.isReset && this.view.cx === 0.5 && this.view.cy === 0.5) return;
    this.view.reset();
    this.changed();
  }

  /** Shows content point (u, v) if it is out of view. */
  reveal(u, v) {
    if (this.view.reveal(u, v)) this.changed();
  }

  wheel(e) {
    const height = e.currentTarget?.getBoundingClientRect().height ?? 500;
    const dy = wheelPixels(e, height);
    // At the whole picture, scrolling down scrolls the page, as it would without the map.
    if (!dy || (this.view.isReset && dy > 0 && !e.ctrlKey)) return;
    e.preventDefault();
    // A trackpad's pinch comes as a wheel with Ctrl and small steps.
    const factor = clamp(Math.exp(-dy * (e.ctrlKey ? 0.01 : 0.002)), 0.5, 2);
    this.zoomBy(factor, ...this.fractions(e));
  }

  down(e) {
    if (e.pointerType === 'mouse' && e.button !== 0) return;
    const el = e.currentTarget;
    this.pointers.set(e.pointerId, { x: e.clientX, y: e.clientY, el });
    if (this.pointers.size === 2) {
      // The content point under the midpoint stays under it; the zoom follows the distance.
      const start = this.pinchState();
      const [fx, fy] = this.fractionsOf(start.mx, start.my, start.el);
      const [u, v] = this.view.toContent(fx, fy);
      this.gesture = { kind: 'pinch', u, v, zoom: this.view.zoom, dist: start.dist, el: start.el };
      for (const id of this.pointers.keys()) el.setPointerCapture?.(id);
      this.onPinch?.();
      e.preventDefault();
    } else if (this.pointers.size === 1) {
      this.gesture = { kind: this.dragPans() ? 'drag' : 'tap-only', x: e.clientX, y: e.clientY, moved: false, id: e.pointerId };
      if (this.gesture.kind === 'drag') el.setPointerCapture?.(e.pointerId);
    } else {
      this.gesture = null;
    }
  }

  /** The two pointers' midpoint and distance, in CSS pixels. */
  pinchState() {
    const [a, b] = [...this.pointers.values()];
    return { mx: (a.x + b.x) / 2, my: (a.y + b.y) / 2, dist: Math.hypot(a.x - b.x, a.y - b.y) || 1, el: a.el };
  }

  move(e) {
    const p = this.pointers.get(e.pointerId);
    if (!p) return;
    const g = this.gesture;
    const last = { x: p.x, y: p.y };
    p.x = e.clientX;
    p.y = e.clientY;
    if (!g) return;
    if (g.kind === 'pinch') {
      const now = this.pinchState();
      const [fx, fy] = this.fractionsOf(now.mx, now.my, g.el);
      if (this.view.pinchTo(g.u, g.v, (g.zoom * now.dist) / g.dist, fx, fy)) this.changed();
      return;
    }
    if (!g.moved && Math.hypot(e.clientX - g.x, e.clientY - g.y) <= TAP_SLOP) return;
    g.moved = true;
    if (g.kind === 'drag') {
      const r = p.el.getBoundingClientRect();
      this.panBy((e.clientX - last.x) / (r.width || 1), (e.clientY - last.y) / (r.height || 1));
    }
  }

  up(e, done) {
    if (!this.pointers.has(e.pointerId)) return;
    const g = this.gesture;
    this.pointers.delete(e.pointerId);
    if (g && g.kind !== 'pinch' && g.id === e.pointerId && done && !g.moved && this.onTap) {
      this.onTap(e, ...this.contentAt(e));
    }
    // A pinch that loses a finger does not turn into a drag.
    this.gesture = this.pointers.size === 0 ? null : g?.kind === 'pinch' ? { kind: 'none' } : g;
  }

  /** Whether a pinch or a drag that moved the view is going on. */
  get busy() {
    const g = this.gesture;
    return Boolean(g && (g.kind === 'pinch' || g.kind === 'none' || (g.kind === 'drag' && g.moved)));
  }

  key(e) {
    if (e.ctrlKey || e.metaKey || e.altKey) return;
    const pan = e.shiftKey ? 0.5 : PAN_STEP;
    switch (e.key) {
      case '+':
      case '=':
        this.zoomBy(ZOOM_STEP);
        break;
      case '-':
      case '_':
        this.zoomBy(1 / ZOOM_STEP);
        break;
      case '0':
        this.reset();
        break;
      case 'ArrowLeft':
      case 'ArrowRight':
      case 'ArrowUp':
      case 'ArrowDown': {
        const d = { ArrowLeft: [pan, 0], ArrowRight: [-pan, 0], ArrowUp: [0, pan], ArrowDown: [0, -pan] }[e.key];
        // At the edge, the key does what it would do without the map (scroll the page).
        if (!this.view.panBy(...d)) return;
        this.changed();
        break;
      }
      default:
        return;
    }
    e.preventDefault();
  }

  /** − + and Fit buttons, for touch screens and for anyone without a wheel. */
  makeControls({ className = 'zoom-controls', label = 'Zoom' }) {
    const group = document.createElement('div');
    group.className = className;
    group.setAttribute('role', 'group');
    group.setAttribute('aria-label', label);
    const button = (text, title, fn) => {
      const b = document.createElement('button');
      b.type = 'button';
      b.textContent = text;
      b.title = title;
      b.setAttribute('aria-label', title);
      b.addEventListener('click', fn);
      group.append(b);
      return b;
    };
    this.outButton = button('−', 'Zoom out (−)', () => this.zoomBy(1 / ZOOM_STEP));
    this.inButton = button('+', 'Zoom in (+)', () => this.zoomBy(ZOOM_STEP));
    this.fitButton = button('Fit', 'Show the whole picture (0)', () => this.reset());
    this.fitButton.dataset.zoom = 'fit';
    return group;
  }

  update() {
    if (!this.controls) return;
    const v = this.view;
    this.outButton.disabled = v.isReset;
    this.inButton.disabled = v.zoom >= v.maxZoom;
    this.fitButton.disabled = v.isReset;
    this.controls.dataset.zoom = v.zoom.toFixed(2);
    this.fitButton.textContent = v.isReset ? 'Fit' : `Fit (${Math.round(v.zoom * 100)} %)`;
  }

  /**
   * Draws `source` (an ImageBitmap, canvas or image, any size) on `canvas` through the view.
   * By default the source is the whole picture and fills the canvas at zoom 1; with `width`
   * and `height` the whole picture is that many source pixels and the source is a part of it
   * whose top left corner is at (`x`, `y`). Crisp when enlarged (cells stay square), smooth
   * when shrunk (thin lines survive); `clear: false` draws over what is there.
   */
  draw(canvas, source, { clear = true, x = 0, y = 0, width = source.width, height = source.height } = {}) {
    const ctx = canvas.getContext('2d');
    const t = this.view.transform(canvas.width, canvas.height, width, height);
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    if (clear) ctx.clearRect(0, 0, canvas.width, canvas.height);
    ctx.imageSmoothingEnabled = t[0] < 0.999;
    ctx.setTransform(...t);
    ctx.drawImage(source, x, y);
    ctx.setTransform(1, 0, 0, 1, 0, 0);
  }
}
