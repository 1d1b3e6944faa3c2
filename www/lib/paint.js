// Brush painting on an array of cell codes (0 free, 1 unknown, 2 occupied), row-major.
// Pure functions, no DOM: the page keeps the codes, paints here, and has the wasm library
// rebuild and render the map.

/** Cell codes of eq. 3.7. */
export const FREE = 0;
export const UNKNOWN = 1;
export const OCCUPIED = 2;

/** What each tool writes; `null` restores the cell as it was loaded (the eraser). */
export const TOOLS = Object.freeze({ occupied: OCCUPIED, free: FREE, unknown: UNKNOWN, eraser: null });

/** The largest brush, in cells across. */
export const MAX_BRUSH = 64;

/**
 * Offsets [dx, dy] of a round brush `size` cells across (1 is a single cell).
 * @param {number} size
 * @returns {Array<[number, number]>}
 */
export function brushOffsets(size) {
  const s = Math.min(MAX_BRUSH, Math.max(1, Math.floor(Number(size) || 1)));
  const reach = Math.floor(s / 2); // `0 - reach`, not `-reach`: no -0 offsets
  const r2 = (s / 2) ** 2;
  const out = [];
  for (let dy = 0 - reach; dy <= reach; dy++) {
    for (let dx = 0 - reach; dx <= reach; dx++) {
      if (dx * dx + dy * dy <= r2) out.push([dx, dy]);
    }
  }
  return out;
}

/**
 * Paints the brush centred on cell (cx, cy).
 * @param {Uint8Array} codes the map being painted, `width * height` codes
 * @param {Uint8Array} base the map as loaded, where the eraser reads
 * @param {number} width
 * @param {number} height
 * @param {number} cx
 * @param {number} cy
 * @param {Array<[number, number]>} offsets from {@link brushOffsets}
 * @param {number|null} value a code, or null to restore `base`
 * @returns {number} how many cells changed
 */
export function stamp(codes, base, width, height, cx, cy, offsets, value) {
  let changed = 0;
  for (const [dx, dy] of offsets) {
    const x = cx + dx;
    const y = cy + dy;
    if (x < 0 || y < 0 || x >= width || y >= height) continue;
    const i = y * width + x;
    const v = value === null ? base[i] : value;
    if (codes[i] !== v) {
      codes[i] = v;
      changed++;
    }
  }
  return changed;
}

/**
 * The cells on the straight line from (x0, y0) to (x1, y1), both ends included (Bresenham).
 * @returns {Array<[number, number]>}
 */
export function line(x0, y0, x1, y1) {
  const out = [];
  const dx = Math.abs(x1 - x0);
  const dy = -Math.abs(y1 - y0);
  const sx = x0 < x1 ? 1 : -1;
  const sy = y0 < y1 ? 1 : -1;
  let err = dx + dy;
  let x = x0;
  let y = y0;
  for (;;) {
    out.push([x, y]);
    if (x === x1 && y === y1) return out;
    const e2 = 2 * err;
    if (e2 >= dy) {
      err += dy;
      x += sx;
    }
    if (e2 <= dx) {
      err += dx;
      y += sy;
    }
  }
}

/**
 * Paints a stroke segment: the brush at every cell from `from` to `to` (both included), so that
 * a fast pointer still leaves a continuous line.
 * @returns {number} how many cells changed
 */
export function strokeTo(codes, base, width, height, from, to, offsets, value) {
  let changed = 0;
  for (const [x, y] of line(from[0], from[1], to[0], to[1])) {
    changed += stamp(codes, base, width, height, x, y, offsets, value);
  }
  return changed;
}

/**
 * The cell under a point given in CSS pixels relative to the displayed map's top-left corner,
 * clamped to the map.
 * @param {number} px
 * @param {number} py
 * @param {{width: number, height: number}} shown the displayed size in CSS pixels
 * @param {number} width map width in cells
 * @param {number} height map height in cells
 * @returns {[number, number]}
 */
export function cellAt(px, py, shown, width, height) {
  const clamp = (v, hi) => Math.min(hi - 1, Math.max(0, v));
  return [
    clamp(Math.floor((px / shown.width) * width), width),
    clamp(Math.floor((py / shown.height) * height), height),
  ];
}
