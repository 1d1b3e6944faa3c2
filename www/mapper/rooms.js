// The best world's rooms on the live mapper: read from the worker (RoomsFeed: never two
// requests at once; while the chain runs, at most every ROOMS_EVERY_MS and at most ROOMS_SHARE
// of the worker's time), shown in the Rooms
// table, and pointed at: the room under the mouse, the table row in focus or a pinned room is
// highlighted on the map with its type, area, doors and type marginals in a box beside it.
// The rooms' details (the room of every cell) are read only while someone points at rooms.

import { formatNumber } from '../lib/plot.js';
import { turnDue } from '../lib/scheduler.js';
import { fillRoomInfo, RoomIndex } from '../lib/room-info.js';
import { showError, state, ui } from './state.js';
import { refreshSelection } from './edits.js';
import { paintMain, refresh3d } from './view.js';
import { updateSides } from './weak.js';

/** While the chain runs, the rooms are read at most this often (the worker computes them). */
const ROOMS_EVERY_MS = 2000;
/**
 * While the chain runs, finding the rooms takes at most this share of the time: on a large map
 * the worker's room layer takes a second or more, which the chain would otherwise wait for
 * every 2 s (office_e: 9.3 s to settled with rooms every 2 s, 5.5 s with none).
 */
const ROOMS_SHARE = 0.2;
/** The room types, in the order the page lists them. */
const ROOM_TYPES = ['room', 'corridor', 'hall', 'other', 'unknown'];

/**
 * The best world's rooms of one chain, read from its worker (`roomsJson`, computed there):
 * never more than one request on its way; one asked for meanwhile follows when it is back.
 */
export class RoomsFeed {
  /**
   * @param {() => RemoteChain} chain  the chain's worker
   * @param {(rooms: object[] | null, details: object | null) => void} show  called with the
   *   rooms (null: none read yet) and their details, if wanted and read for these rooms
   * @param {() => void} [replied]  called after each reply of the chain's worker, changed or
   *   not: the worker has the plan of its best world now, which the map draws room by room
   */
  constructor(chain, show, replied = () => {}) {
    this.chain = chain;
    this.show = show;
    this.replied = replied;
    /**
     * Whether the rooms' details are wanted: their type marginals and the room of every cell
     * (for pointing at rooms). Read only while wanted: the labels are two bytes per cell, and
     * reading them every 2 s on a large map makes garbage enough for a long collection.
     */
    this.details = false;
    this.generation = -1;
    this.rooms = null;
    /** { types, labels } of the rooms, and the rooms' text they were read with. */
    this.extra = null;
    this.extraText = null;
    /** The rooms' JSON text as last read. */
    this.text = null;
    this.inFlight = false;
    this.again = false;
    this.at = 0;
    /** When the last reply came, and how long its request took, ms. */
    this.doneAt = 0;
    this.tookMs = 0;
    this.readAt = -1;
  }

  /** A new chain: forget the old one's rooms and read the new one's. */
  restart(generation, iteration) {
    this.generation = generation;
    this.rooms = null;
    this.extra = null;
    this.extraText = null;
    this.text = null;
    this.readAt = iteration;
    this.show(null);
    this.request();
  }

  /**
   * Keeps the rooms up to date with the chain whose numbers are `stats`: every ROOMS_EVERY_MS
   * while it runs, and once more when it has stopped (paused, settled or stepped).
   */
  follow(stats, running, now) {
    if (!stats || stats.generation !== this.generation) return;
    if (running) {
      if (!this.inFlight && now - this.at >= ROOMS_EVERY_MS && turnDue(this.doneAt, this.tookMs, ROOMS_SHARE)) {
        this.readAt = stats.iteration;
        this.request();
      }
    } else if (this.readAt !== stats.iteration) {
      this.readAt = stats.iteration;
      this.request();
    }
  }

  /** Details wanted or not; wanted and not read for the rooms shown, they are read now. */
  want(on) {
    this.details = on;
    if (on && this.generation >= 0 && (this.extraText === null || this.extraText !== this.text)) this.request();
  }

  /** The details, if they are those of the rooms shown. */
  get fresh() {
    return this.extra && this.extraText === this.text ? this.extra : null;
  }

  /** Whether the rooms shown are those of the chain at `stats`, with nothing on its way. */
  current(stats) {
    return !this.inFlight && !this.again && stats?.generation === this.generation && this.readAt === stats.iteration;
  }

  request() {
    if (this.inFlight) {
      this.again = true;
      return;
    }
    this.inFlight = true;
    this.again = false;
    this.at = performance.now();
    const generation = this.generation;
    this.chain()
      .call('rooms', { details: this.details, known: this.rooms ? this.text : null, knownDetails: this.extra ? this.extraText : null })
      .then(
        (reply) => {
          if (generation !== this.generation) {
            this.again = true;
            return;
          }
          this.replied();
          // The same rooms as last time (the best world has not changed): nothing to redo.
          if (reply.same) return;
          this.text = reply.text;
          this.rooms = JSON.parse(reply.text);
          if (reply.types !== null) {
            this.extra = { types: JSON.parse(reply.types), labels: reply.labels };
            this.extraText = reply.text;
          }
          this.show(this.rooms, this.fresh);
        },
        (err) => showError(err),
      )
      .finally(() => {
        this.doneAt = performance.now();
        this.tookMs = this.doneAt - this.at;
        this.inFlight = false;
        if (this.again) this.request();
      });
  }

}

/** "3 rooms, 1 corridor" for a rooms list. */
export function roomsByType(rooms) {
  const counts = new Map();
  for (const r of rooms) counts.set(r.type, (counts.get(r.type) ?? 0) + 1);
  const order = (t) => (ROOM_TYPES.indexOf(t) + ROOM_TYPES.length + 1) % (ROOM_TYPES.length + 1);
  return [...counts].sort(([a], [b]) => order(a) - order(b) || a.localeCompare(b)).map(([t, n]) => `${n} ${t}`).join(', ');
}

/** The texts of a Rooms table row for room `r`, cell by cell. */
function rowTexts(r) {
  return [
    r.name ? `${r.id} ${r.name}` : String(r.id),
    r.type,
    formatNumber(r.area_m2, 1),
    r.units.join(', '),
    r.opens_to.length ? r.opens_to.join(', ') : '–',
  ];
}

/**
 * The row of room `r`: `tr` (the row it had) with only its changed texts and attributes set,
 * or a new row. A row left as it was costs the page no layout: the table is read again every
 * few seconds while the chain runs, and remaking all its rows made each reading a full layout
 * and paint of the page (25 - 60 ms on a busy 2-core machine, over a frame's budget).
 */
function roomRow(r, tr) {
  const row = tr ?? document.createElement('tr');
  if (!tr) row.tabIndex = 0;
  const set = (name, value) => {
    if (row.dataset[name] !== value) row.dataset[name] = value;
  };
  set('room', String(r.id));
  set('type', r.type);
  const selected = String(state.selected?.room === r.id);
  if (row.getAttribute('aria-selected') !== selected) row.setAttribute('aria-selected', selected);
  rowTexts(r).forEach((text, i) => {
    const td = row.cells[i] ?? row.appendChild(document.createElement('td'));
    if (td.textContent !== text) td.textContent = text;
  });
  return row;
}

/**
 * The Rooms table shows `rooms`, in their order: the rows of rooms it already shows are kept
 * (their changed cells set), and the children are replaced only if the rows themselves change.
 */
function updateRoomRows(rooms) {
  const old = new Map([...ui.rooms.rows].map((tr) => [tr.dataset.room, tr]));
  const rows = rooms.map((r) => roomRow(r, old.get(String(r.id))));
  const same = rows.length === ui.rooms.rows.length && rows.every((tr, i) => ui.rooms.rows[i] === tr);
  if (same) return;
  // The row in focus is moved or remade: focus goes back to its room's row, so that the
  // keyboard stays put.
  const focused = ui.rooms.contains(document.activeElement) ? document.activeElement.dataset.room : null;
  ui.rooms.replaceChildren(...rows);
  if (focused && document.activeElement?.dataset.room !== focused) ui.rooms.querySelector(`tr[data-room="${focused}"]`)?.focus({ preventScroll: true });
}

/**
 * The rooms table and the rooms count of the main chain, and the rooms the map points at
 * (`details`: their type marginals and the room of every cell).
 */
export function showRooms(rooms, details) {
  ui.stat.rooms.textContent = rooms ? String(rooms.length) : '–';
  ui.stats.dataset.rooms = rooms ? String(rooms.length) : '';
  const m = state.map;
  state.roomIndex = rooms && details && m ? new RoomIndex(rooms, details.types, details.labels, m.width, m.height) : null;
  updateRoomRows(rooms ?? []);
  refreshHover();
  // The details came while the pointer or the focus waited for them.
  if (!state.hover.id && state.roomIndex) {
    if (ui.rooms.contains(document.activeElement)) pointRoom(document.activeElement.closest('tr'), true);
    else if (state.pointer && !state.painting) setHover(roomAt(...state.viewport.contentAt(state.pointer, ui.canvas)), state.pointer);
  }
  ui.roomsSummary.textContent = !rooms
    ? 'Reading the best world\'s rooms…'
    : rooms.length === 0
      ? 'The best world has no rooms yet.'
      : `The best world's ${rooms.length} room${rooms.length === 1 ? '' : 's'}: ${roomsByType(rooms)} (units merged where no wall parts them, as in world.json). Click a row to select the room.`;
  updateSides();
  // A route and the 3D view follow the best world.
  if (rooms) {
    state.route?.refresh();
    refresh3d();
  }
  if (rooms && state.selected) refreshSelection();
}

/**
 * Shows room `id` (0: none) of the best world: its cells highlighted on the map, and its type,
 * area, doors, units and type marginals in the info box, beside `anchor` (a pointer's client
 * position) or, without one, beside the room. A `pinned` room (clicked or tapped) stays when
 * the pointer leaves; Escape, or a click outside any room, hides it.
 */
export function setHover(id, anchor = null, pinned = false) {
  const h = state.hover;
  const room = id ? state.roomIndex?.rooms.get(id) : null;
  const shown = room ? id : 0;
  h.pinned = Boolean(shown) && pinned;
  h.anchor = anchor;
  if (shown !== h.id) {
    h.id = shown;
    h.mask = shown ? state.roomIndex.mask(shown) : null;
    paintMain();
    if (shown) fillRoomInfo(ui.roomInfo, room, state.roomIndex.types.get(shown), state.roomIndex.rooms);
  }
  ui.roomInfo.hidden = !shown;
  ui.roomInfo.dataset.pinned = String(h.pinned);
  if (!shown) delete ui.roomInfo.dataset.room;
  placeRoomInfo();
}

/** The rooms were read again: the room shown is shown as it is now (hidden if it is gone). */
function refreshHover() {
  const h = state.hover;
  if (!h.id) return;
  const id = h.id;
  h.id = 0;
  h.mask = null;
  setHover(id, h.anchor, h.pinned);
}

/** Puts the info box beside its anchor (or its room), inside the stage. */
export function placeRoomInfo() {
  const box = ui.roomInfo;
  const h = state.hover;
  if (box.hidden || !h.id) return;
  const stage = ui.stage.getBoundingClientRect();
  let x;
  let y;
  if (h.anchor) {
    x = h.anchor.clientX - stage.left + 16;
    y = h.anchor.clientY - stage.top + 16;
  } else {
    const b = state.roomIndex.box(h.id);
    const m = state.map;
    const c = ui.canvas.getBoundingClientRect();
    const [fx, fy] = b ? state.viewport.view.toElement(b.cx / m.width, b.cy / m.height) : [0.5, 0.5];
    x = c.left - stage.left + Math.min(1, Math.max(0, fx)) * c.width + 12;
    y = c.top - stage.top + Math.min(1, Math.max(0, fy)) * c.height + 12;
  }
  const w = box.offsetWidth;
  const hh = box.offsetHeight;
  if (x + w > stage.width) x = Math.max(0, x - w - 32);
  if (y + hh > stage.height) y = Math.max(0, stage.height - hh);
  box.style.left = `${Math.round(x)}px`;
  box.style.top = `${Math.round(y)}px`;
}

/** The room under the content point (u, v) of the map, or 0. */
function roomAt(u, v) {
  return state.roomIndex ? state.roomIndex.atContent(u, v) : 0;
}

/**
 * The rooms' details (type marginals, the room of every cell) are read from the worker only
 * while someone points at rooms: the mouse on the map, the Rooms table in use, a room pinned.
 */
function wantRoomDetails() {
  state.rooms?.want(Boolean(state.pointer || state.tableInUse || state.hover.pinned));
}

/** A mouse or pen over the map shows the room under it. */
export function onHover(e) {
  if (e.pointerType !== 'mouse' && e.pointerType !== 'pen') return;
  const wanted = !state.pointer;
  state.pointer = { clientX: e.clientX, clientY: e.clientY };
  if (wanted) wantRoomDetails();
  if (e.buttons || state.painting || state.hover.pinned) return;
  setHover(roomAt(...state.viewport.contentAt(e, ui.canvas)), state.pointer);
}

export function onLeave() {
  state.pointer = null;
  if (!state.hover.pinned) setHover(0);
  wantRoomDetails();
}

/** A click or tap that did not drag: pins the room there, or unpins. */
export function onTap(e, u, v) {
  if (state.painting || e.currentTarget !== ui.canvas) return;
  const id = roomAt(u, v);
  if (!id || (state.hover.pinned && state.hover.id === id)) setHover(0);
  else setHover(id, { clientX: e.clientX, clientY: e.clientY }, true);
  wantRoomDetails();
}

/** A row of the Rooms table in focus (or under the mouse): its room on the map, in view. */
function pointRoom(tr, reveal) {
  const id = Number(tr?.dataset.room);
  // The mouse passing over the table leaves a pinned room; the keyboard moves on from it.
  if (!id || (!reveal && state.hover.pinned)) return;
  setHover(id);
  const b = reveal && state.roomIndex?.box(id);
  if (b) state.viewport.reveal(b.cx / state.map.width, b.cy / state.map.height);
}

/**
 * The Rooms table in use (focus in it, or the mouse over it) points at its rows' rooms on the
 * map; Escape hides the room shown.
 */
export function wireRooms() {
  const tableUse = (on) => {
    state.tableInUse = on || ui.rooms.contains(document.activeElement) || ui.rooms.matches(':hover');
    wantRoomDetails();
  };
  ui.rooms.addEventListener('focusin', (e) => {
    tableUse(true);
    pointRoom(e.target.closest('tr'), true);
  });
  ui.rooms.addEventListener('focusout', (e) => {
    if (!state.hover.pinned) setHover(0);
    tableUse(ui.rooms.contains(e.relatedTarget));
  });
  ui.rooms.addEventListener('mouseover', (e) => {
    tableUse(true);
    pointRoom(e.target.closest('tr'), false);
  });
  ui.rooms.addEventListener('mouseleave', () => {
    if (!state.hover.pinned && !ui.rooms.contains(document.activeElement)) setHover(0);
    tableUse(false);
  });
  document.addEventListener('keydown', (e) => {
    if (e.key === 'Escape' && state.hover.id) {
      setHover(0);
      wantRoomDetails();
    }
  });
}
