// The rooms of the best world as the reader points at them: which room is under a cell, where
// a room is, its cells as a highlight, and the words and bars that describe it (type, area,
// doors, the rooms it opens to, its units with their full labels and the knowledge base's
// type marginals). The numbers are the library's (roomsJson, roomTypesJson, roomLabels, read
// in the chain's worker); this module only looks them up and lays them out.

/** The four type marginals, in the order shown, with the name the rooms list uses. */
export const MARGINALS = [
  ['room', 'room'],
  ['corridor', 'corridor'],
  ['hall', 'hall'],
  ['other', 'other'],
];

/** Rooms, their types and the room id of every cell, for lookups. */
export class RoomIndex {
  /**
   * @param {object[]} rooms roomsJson's rooms
   * @param {object[] | null} types roomTypesJson's rows (same rooms)
   * @param {Uint16Array | null} labels room id per cell, row-major
   * @param {number} width map width in cells
   * @param {number} height map height in cells
   */
  constructor(rooms, types, labels, width, height) {
    this.rooms = new Map(rooms.map((r) => [r.id, r]));
    this.types = new Map((types ?? []).map((t) => [t.id, t]));
    this.labels = labels && labels.length === width * height ? labels : null;
    this.width = width;
    this.height = height;
    this.boxes = new Map();
  }

  /** The id of the room at cell (x, y), or 0. */
  at(x, y) {
    if (!this.labels || x < 0 || y < 0 || x >= this.width || y >= this.height) return 0;
    return this.labels[y * this.width + x];
  }

  /** The room at content point (u, v) (fractions of the map), or 0. */
  atContent(u, v) {
    return this.at(Math.floor(u * this.width), Math.floor(v * this.height));
  }

  /** The cells' bounding box of room `id` and their mean position, or null if it has none. */
  box(id) {
    if (this.boxes.has(id)) return this.boxes.get(id);
    let box = null;
    if (this.labels) {
      let [x0, y0, x1, y1, sx, sy, n] = [Infinity, Infinity, -1, -1, 0, 0, 0];
      const w = this.width;
      for (let i = 0; i < this.labels.length; i++) {
        if (this.labels[i] !== id) continue;
        const x = i % w;
        const y = (i - x) / w;
        if (x < x0) x0 = x;
        if (x > x1) x1 = x;
        if (y < y0) y0 = y;
        if (y > y1) y1 = y;
        sx += x;
        sy += y;
        n++;
      }
      if (n) box = { x0, y0, x1: x1 + 1, y1: y1 + 1, cx: sx / n + 0.5, cy: sy / n + 0.5, cells: n };
    }
    this.boxes.set(id, box);
    return box;
  }

  /**
   * Room `id`'s cells as a picture (its bounding box, one pixel per cell): `edge` on the cells
   * at its border, `fill` on the others, clear outside the room; with where it goes on the
   * map. Null if it has no cells.
   */
  mask(id, { fill = [255, 196, 0, 90], edge = [214, 90, 0, 255] } = {}) {
    const b = this.box(id);
    if (!b) return null;
    const w = b.x1 - b.x0;
    const h = b.y1 - b.y0;
    const image = new ImageData(w, h);
    const d = image.data;
    const inRoom = (x, y) => this.at(x, y) === id;
    for (let y = 0; y < h; y++) {
      const my = b.y0 + y;
      for (let x = 0; x < w; x++) {
        const mx = b.x0 + x;
        if (!inRoom(mx, my)) continue;
        const border = !inRoom(mx - 1, my) || !inRoom(mx + 1, my) || !inRoom(mx, my - 1) || !inRoom(mx, my + 1);
        d.set(border ? edge : fill, 4 * (y * w + x));
      }
    }
    const canvas = document.createElement('canvas');
    canvas.width = w;
    canvas.height = h;
    canvas.getContext('2d').putImageData(image, 0, 0);
    return { canvas, x: b.x0, y: b.y0 };
  }
}

const fmt = (v, digits = 0) =>
  Number(v).toLocaleString('en-US', { minimumFractionDigits: digits, maximumFractionDigits: digits });

const list = (ids) => (ids.length ? ids.join(', ') : 'none');

function el(tag, className, text) {
  const e = document.createElement(tag);
  if (className) e.className = className;
  if (text !== undefined) e.textContent = text;
  return e;
}

/**
 * Where each door of `room` leads, as text: "door 10 to room 3" (a door lists both rooms it
 * joins, so the other is the room of `rooms` that lists it too), "door 7 within the room" for a
 * door whose two sides are this room; "none" without doors. Ids, so they read as ids, not counts.
 */
export function doorText(room, rooms) {
  if (!room.doors.length) return 'none';
  return room.doors
    .map((d) => {
      const others = [...(rooms?.values() ?? [])].filter((r) => r.id !== room.id && r.doors.includes(d)).map((r) => `room ${r.id}`);
      return others.length ? `door ${d} to ${others.join(' and ')}` : `door ${d} within the room`;
    })
    .join(', ');
}

/** The rooms `room` opens to, as text: "room 3, room 5", or "none". */
export function opensText(room) {
  return room.opens_to.length ? room.opens_to.map((r) => `room ${r}`).join(', ') : 'none';
}

/** A unit's label in full, as the map writes it before shortening it: "corridor 12". */
export function unitLabel(unit) {
  return `${unit.type} ${unit.id}`;
}

/** One line of text saying what the info box says (for screen readers and tests); `rooms`: all rooms by id. */
export function roomSummary(room, types, rooms) {
  const m = types?.marginals;
  const p = m ? MARGINALS.map(([k, name]) => `${name} ${fmt(m[k], 2)}`).join(', ') : 'none';
  const units = types?.units?.length ? types.units.map(unitLabel).join(', ') : list(room.units);
  return `Room ${room.id}${room.name ? ` “${room.name}”` : ''}, ${room.type}, ${fmt(room.area_m2, 1)} m², ${doorText(room, rooms)}, ` +
    `opens to ${opensText(room)}, units ${units}; type marginals ${p}`;
}

/**
 * Fills `box` with room `room`: a title, its area, doors and neighbours, its units with their
 * full labels, and a bar per type marginal. `rooms` (all rooms by id) says where its doors lead.
 */
export function fillRoomInfo(box, room, types, rooms) {
  const head = el('p', 'room-info-title');
  head.append(el('strong', '', `Room ${room.id}`), room.name ? ` “${room.name}”` : '', ` · ${room.type}`);
  const facts = el('p', 'room-info-facts');
  facts.append(
    el('span', 'room-info-area', `${fmt(room.area_m2, 1)} m²`),
    ' · ',
    el('span', 'room-info-doors', room.doors.length ? doorText(room, rooms) : 'no doors'),
    ' · ',
    el('span', 'room-info-opens', `opens to: ${opensText(room)}`),
  );
  const units = el('p', 'room-info-units',
    `units: ${types?.units?.length ? types.units.map(unitLabel).join(', ') : list(room.units)}`);
  const parts = [head, facts, units];
  if (room.type === 'unknown') {
    parts.push(el('p', 'room-info-unknown',
      'Unexplored: space the sensor saw only as rays (through a window or an open door), or free space no unit explains.'));
  }
  const m = types?.marginals;
  if (m) {
    const table = el('table', 'room-info-marginals');
    table.append(el('caption', '', 'Type marginals'));
    for (const [key, name] of MARGINALS) {
      const tr = el('tr');
      tr.dataset.type = key;
      const bar = el('span', 'bar');
      bar.style.width = `${Math.round(100 * Math.min(1, Math.max(0, m[key])))}%`;
      const cell = el('td', 'bar-cell');
      cell.append(bar);
      tr.append(el('th', '', name), el('td', 'p', fmt(m[key], 2)), cell);
      table.append(tr);
    }
    parts.push(table);
  } else {
    parts.push(el('p', 'room-info-none', 'No type marginals: no unit of the world covers this room.'));
  }
  box.replaceChildren(...parts);
  box.dataset.room = String(room.id);
  box.setAttribute('aria-label', roomSummary(room, types));
}
