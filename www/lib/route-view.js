// Route mode of the live mapper: pick a start and a goal on the map (click them, or type their
// cells), and see the route the chain's worker plans through the best world's rooms and doors
// (`Mapper.route`, as `ksmcmc route` plans it): the path drawn over the map on a layer of its
// own, and the rooms and doors it passes listed beside it. The goal may be a placeholder of the
// best world (a frontier, with the probability that it leads to a room not yet in the map), as
// `ksmcmc route --to-placeholder` plans to it.

import { cellAt } from './paint.js';
import { formatNumber } from './plot.js';

/**
 * A cell typed as `X,Y` (column, row; a space may stand for the comma).
 * @returns {[number, number]}
 */
export function parseCell(text) {
  const m = /^\s*(-?\d+)\s*[,\s]\s*(-?\d+)\s*$/.exec(text);
  if (!m) throw new Error(`"${text.trim()}" is not a cell: write its column and row, e.g. 120,45.`);
  return [Number(m[1]), Number(m[2])];
}

/** The likeliest of a placeholder's types (`room`, `corridor`, `hall` or `other`). */
export function likeliest(types) {
  return Object.entries(types).reduce((best, t) => (t[1] > best[1] ? t : best))[0];
}

/** The path's colour, its outline, and the two ends'. */
const PATH = '#c2185b';
const OUTLINE = 'rgba(255, 255, 255, 0.9)';
const START = '#00875a';
const GOAL = '#d32f2f';

export class RouteView {
  /**
   * @param {object} ui  the elements: `canvas` (the map), `layer` (the canvas over it),
   *   `toggle` (the route-mode button), `from` and `to` (text inputs), `placeholder` (a
   *   select of the placeholders), `summary`, `rooms` and `doors` (where the route is
   *   described)
   * @param {object} host  `plan(from, to)`: a promise of the route's JSON text;
   *   `placeholders()`: a promise of the best world's placeholders' JSON text; `rooms()`: the
   *   best world's rooms as last read (or null); `size()`: the map's `{ width, height }`
   */
  constructor(ui, host) {
    this.ui = ui;
    this.host = host;
    this.active = false;
    /** The ends as picked, [x, y] each, and the route planned between them. */
    this.from = null;
    this.to = null;
    this.result = null;
    this.error = null;
    /** Counts requests: a reply to an older one is dropped. */
    this.token = 0;
    this.busy = false;
    this.scale = 1;
    /** The best world's placeholders as last read, and the request for them on its way. */
    this.placeholders = [];
    this.listToken = 0;
  }

  /**
   * Reads the best world's placeholders again and lists them in the select, most likely to
   * lead to a new room first. The select keeps the one chosen if it is still there.
   */
  async listPlaceholders() {
    if (!this.host.placeholders || !this.ui.placeholder) return;
    const token = ++this.listToken;
    let list = [];
    try {
      list = JSON.parse(await this.host.placeholders());
    } catch {
      list = [];
    }
    if (token !== this.listToken) return;
    this.placeholders = list;
    const select = this.ui.placeholder;
    const kept = select.value;
    const sorted = [...list].sort((a, b) => b.p_new_room - a.p_new_room || a.id - b.id);
    const none = document.createElement('option');
    none.value = '';
    none.textContent = list.length ? `Choose one of ${list.length}` : 'No placeholders: the map has no frontier';
    select.replaceChildren(
      none,
      ...sorted.map((p) => {
        const o = document.createElement('option');
        o.value = String(p.id);
        o.textContent = `#${p.id}: ${Math.round(100 * p.p_new_room)} % new room, likely a ${likeliest(p.types)} (${p.room ? `from room ${p.room}` : 'from no room'})`;
        return o;
      }),
    );
    select.value = sorted.some((p) => String(p.id) === kept) ? kept : '';
    select.disabled = list.length === 0;
  }

  /** Makes placeholder `id` (its `value` in the select) the goal, and plans if the start is set. */
  toPlaceholder(id) {
    const p = this.placeholders.find((q) => String(q.id) === String(id));
    if (!p) return Promise.resolve();
    this.to = [p.x, p.y];
    this.ui.to.value = this.to.join(',');
    this.result = null;
    this.error = null;
    this.show();
    this.draw();
    return this.from ? this.request() : Promise.resolve();
  }

  /** Turns route mode on or off (the ends and the route stay shown). */
  setActive(on) {
    this.active = on;
    this.ui.toggle.setAttribute('aria-pressed', String(on));
    this.ui.canvas.classList.toggle('routing', on);
    if (on) {
      this.ui.canvas.focus({ preventScroll: true });
      this.listPlaceholders();
    }
  }

  /** A pointer press on the map in route mode: the start, then the goal, then a new start. */
  pick(event) {
    const r = this.ui.canvas.getBoundingClientRect();
    const { width, height } = this.host.size();
    const cell = this.host.cellOf ? this.host.cellOf(event) : cellAt(event.clientX - r.left, event.clientY - r.top, r, width, height);
    if (!this.from || this.to) {
      this.from = cell;
      this.to = null;
      this.result = null;
      this.error = null;
      this.token++;
      this.busy = false;
    } else {
      this.to = cell;
    }
    this.ui.from.value = this.from ? this.from.join(',') : '';
    this.ui.to.value = this.to ? this.to.join(',') : '';
    this.show();
    this.draw();
    return this.to ? this.request() : Promise.resolve();
  }

  /** The typed ends (throws if they are not cells). */
  submit() {
    this.from = parseCell(this.ui.from.value);
    this.to = parseCell(this.ui.to.value);
    return this.request();
  }

  /** Plans the route between the ends again (the best world changed), if both are set. */
  refresh() {
    if (this.active) this.listPlaceholders();
    return this.from && this.to ? this.request() : Promise.resolve();
  }

  /** Forgets the ends and the route (another map). */
  clear() {
    this.token++;
    this.from = this.to = this.result = this.error = null;
    this.busy = false;
    this.ui.from.value = this.ui.to.value = '';
    this.placeholders = [];
    this.listToken++;
    if (this.ui.placeholder) {
      const none = document.createElement('option');
      none.value = '';
      none.textContent = 'No placeholders yet';
      this.ui.placeholder.replaceChildren(none);
      this.ui.placeholder.disabled = true;
    }
    this.show();
    this.draw();
  }

  async request() {
    const token = ++this.token;
    this.busy = true;
    this.show();
    let result = null;
    let error = null;
    try {
      result = JSON.parse(await this.host.plan(this.from, this.to));
    } catch (err) {
      error = err instanceof Error ? err.message : String(err);
    }
    if (token !== this.token) return;
    this.busy = false;
    this.result = result;
    this.error = error;
    this.show();
    this.draw();
  }

  /**
   * Sizes the layer as the map canvas: `scale` pixels per cell, the same size on screen. Costs
   * nothing when nothing changed (the page calls it whenever it lays the map out).
   */
  resize(scale) {
    const { width, height } = this.host.size();
    const layer = this.ui.layer;
    const changed = this.scale !== scale || layer.width !== width * scale || layer.height !== height * scale;
    this.scale = scale;
    if (changed) {
      layer.width = width * scale;
      layer.height = height * scale;
    }
    const { width: cssW, height: cssH } = this.ui.canvas.style;
    const restyled = layer.style.width !== cssW || layer.style.height !== cssH;
    if (restyled) Object.assign(layer.style, { width: cssW, height: cssH });
    // Line widths follow the size on screen: redraw a route when either size changed.
    if ((changed || restyled) && (this.from || this.result)) this.draw();
  }

  /** Draws the path and the ends on the layer. */
  draw() {
    const layer = this.ui.layer;
    const ctx = layer.getContext('2d');
    ctx.clearRect(0, 0, layer.width, layer.height);
    const s = this.scale;
    // Lines and marks of at least 2 screen pixels however the map is shrunk on screen.
    const shrink = layer.width / Math.max(1, layer.getBoundingClientRect().width || layer.width);
    const line = Math.max(2 * shrink, 0.6 * s);
    const at = ([x, y]) => [(x + 0.5) * s, (y + 0.5) * s];
    const path = this.result?.path;
    if (path?.length > 1) {
      ctx.lineJoin = ctx.lineCap = 'round';
      for (const [style, width] of [[OUTLINE, line * 2.2], [PATH, line]]) {
        ctx.beginPath();
        ctx.moveTo(...at(path[0]));
        for (const p of path.slice(1)) ctx.lineTo(...at(p));
        ctx.strokeStyle = style;
        ctx.lineWidth = width;
        ctx.stroke();
      }
    }
    for (const [end, color] of [[this.from, START], [this.to, GOAL]]) {
      if (!end) continue;
      ctx.beginPath();
      ctx.arc(...at(end), line * 2.4, 0, 2 * Math.PI);
      ctx.fillStyle = color;
      ctx.fill();
      ctx.lineWidth = line * 0.8;
      ctx.strokeStyle = OUTLINE;
      ctx.stroke();
    }
  }

  /** Describes the route: length, rooms (with their types) and doors, or why there is none. */
  show() {
    const { summary, rooms, doors } = this.ui;
    const types = new Map((this.host.rooms() ?? []).map((r) => [r.id, r.type]));
    const r = this.result;
    rooms.replaceChildren(
      ...(r?.rooms ?? []).map((id) => {
        const li = document.createElement('li');
        li.dataset.room = String(id);
        li.textContent = `Room ${id}${types.has(id) ? ` (${types.get(id)})` : ''}`;
        return li;
      }),
    );
    doors.textContent = r ? (r.doors.length ? r.doors.map((d) => `door ${d}`).join(', ') : 'none') : '–';
    doors.dataset.doors = r ? r.doors.join(',') : '';
    if (this.busy) summary.textContent = 'Planning the route…';
    else if (this.error) summary.textContent = `No route: ${this.error}`;
    else if (r) {
      summary.textContent =
        `${formatNumber(r.length_m, 2)} m from ${this.from.join(',')} to ${this.to.join(',')}, ` +
        `${r.path.length} cells through ${r.rooms.length} room${r.rooms.length === 1 ? '' : 's'} and ` +
        `${r.doors.length} door${r.doors.length === 1 ? '' : 's'}.`;
    } else if (this.from) summary.textContent = `Start ${this.from.join(',')}: now click the goal.`;
    else summary.textContent = this.active ? 'Click the start on the map.' : 'No route yet.';
  }

  /** For tests: what the view holds. */
  snapshot() {
    return {
      active: this.active, from: this.from, to: this.to, result: this.result, error: this.error, busy: this.busy,
      placeholders: this.placeholders,
    };
  }
}
