// The person's corrections to the best world (lib/edits.js describes and reads them): select a
// room on the map or in the Rooms table, then retype, rename, merge or split it; undo, clear,
// export and import the list. The worker holds the list in force (the chain goes on from its
// world with it); the page shows what the worker says it holds.

import { describeEdit, parseEdits } from '../lib/edits.js';
import { clearError, say, showError, state, ui } from './state.js';
import { invoke } from './chain.js';
import { save } from './exports.js';
import { cellFromEvent, requestRedraw } from './view.js';

/** The edits in force as the worker holds them (Reset keeps them, a new map drops them). */
export function syncEdits() {
  invoke('editsJson').then((text) => showEdits(JSON.parse(text)), showError);
}

function showEdits(list) {
  state.edits = list;
  ui.edit.list.replaceChildren(
    ...list.map((e) => {
      const li = document.createElement('li');
      li.textContent = describeEdit(e);
      return li;
    }),
  );
  ui.edit.list.dataset.count = String(list.length);
  updateEditControls();
}

function updateEditControls() {
  const ready = Boolean(state.stats);
  const selected = ready && Boolean(state.selected?.room);
  for (const c of [ui.edit.type, ui.edit.typeApply, ui.edit.name, ui.edit.nameApply, ui.edit.merge, ui.edit.split]) c.disabled = !selected;
  ui.edit.undo.disabled = ui.edit.clear.disabled = !ready || state.edits.length === 0;
  ui.edit.exportEdits.disabled = ui.edit.importEdits.disabled = !ready;
  ui.edit.merge.setAttribute('aria-pressed', String(state.editMode === 'merge'));
  ui.edit.split.setAttribute('aria-pressed', String(state.editMode === 'split'));
}

/**
 * Sends the whole list to the worker (the chain goes on from its current world with it) and
 * shows what the worker holds; a list it refuses changes nothing and shows why.
 */
async function sendEdits(list, done) {
  try {
    await invoke('setEdits', JSON.stringify(list));
    showEdits(JSON.parse(await invoke('editsJson')));
    state.rooms.request();
    requestRedraw();
    clearError();
    if (done) say(done);
  } catch (err) {
    showError(err);
  }
}

function addEdit(edit) {
  return sendEdits([...state.edits, edit], `Edit: ${describeEdit(edit)}.`);
}

export function undoEdit() {
  if (!state.stats || state.edits.length === 0) return;
  const last = state.edits[state.edits.length - 1];
  sendEdits(state.edits.slice(0, -1), `Undone: ${describeEdit(last)}.`);
}

/** Selects the best world's room at map cell (x, y) (or, with `id`, that room); null: none. */
export async function select(at) {
  setEditMode(null);
  if (!at) {
    state.selected = null;
    showSelection();
    return;
  }
  try {
    state.selected = await state.chain.call('roomAt', at);
  } catch (err) {
    showError(err);
    state.selected = null;
  }
  showSelection();
}

/** The selected cell's room again (the best world changed). */
export function refreshSelection() {
  const { x, y } = state.selected;
  state.chain.call('roomAt', { x, y }).then((s) => {
    if (state.selected?.x === x && state.selected?.y === y && s) {
      state.selected = s;
      showSelection();
    }
  }, showError);
}

function showSelection() {
  const s = state.selected;
  const room = s?.room ? state.rooms.rooms?.find((r) => r.id === s.room) : null;
  ui.edit.selection.textContent = !s
    ? 'Click a room on the map, or a row of the Rooms table, to select it.'
    : !s.room
      ? `No room at (${s.x}, ${s.y}) in the best world.`
      : `Selected: room ${s.room}${room ? ` (${room.type}${room.name ? `, “${room.name}”` : ''})` : ''} at (${s.x}, ${s.y}).`;
  ui.edit.selection.dataset.room = s?.room ? String(s.room) : '';
  if (room && EDIT_TYPE_SET.has(room.type)) ui.edit.type.value = room.type;
  for (const tr of ui.rooms.rows) tr.setAttribute('aria-selected', String(s?.room === Number(tr.dataset.room)));
  drawOverlay();
  updateEditControls();
}

const EDIT_TYPE_SET = new Set(['room', 'corridor', 'hall', 'other']);

export function setEditMode(mode) {
  state.editMode = mode;
  state.splitFrom = null;
  state.splitDrag = false;
  drawOverlay();
  ui.canvas.classList.toggle('editing', Boolean(mode));
  if (mode === 'merge') say('Merge: click the room to merge with on the map or in the Rooms table (Esc cancels).');
  if (mode === 'split') say('Split: drag a line across the room on the map, or click its two ends (Esc cancels).');
  updateEditControls();
}

/**
 * What the edits draw over the map (an SVG in map cells): a ring at the selected room's cell,
 * and a split's line while it is drawn (from `state.splitFrom` to `to`).
 */
export function drawOverlay(to = null) {
  let svg = ui.canvas.parentElement.querySelector('.edit-line');
  const sel = state.selected?.room ? state.selected : null;
  if (!state.map || (!sel && !state.splitFrom)) {
    svg?.remove();
    return;
  }
  const { width, height } = state.map;
  if (!svg) {
    svg = document.createElementNS('http://www.w3.org/2000/svg', 'svg');
    svg.setAttribute('class', 'edit-line');
    svg.setAttribute('aria-hidden', 'true');
    svg.setAttribute('preserveAspectRatio', 'none');
    svg.innerHTML = '<circle class="selected" vector-effect="non-scaling-stroke"/><circle class="from" vector-effect="non-scaling-stroke"/><line vector-effect="non-scaling-stroke"/>';
    ui.canvas.parentElement.append(svg);
  }
  svg.setAttribute('viewBox', `0 0 ${width} ${height}`);
  const cv = ui.canvas;
  Object.assign(svg.style, { left: `${cv.offsetLeft}px`, top: `${cv.offsetTop}px`, width: `${cv.clientWidth}px`, height: `${cv.clientHeight}px` });
  const [ring, from, line] = svg.children;
  const r = Math.max(2, Math.min(width, height) / 40);
  const put = (el, attrs) => {
    el.toggleAttribute('hidden', !attrs);
    el.style.display = attrs ? '' : 'none';
    for (const [k, v] of Object.entries(attrs ?? {})) el.setAttribute(k, v);
  };
  put(ring, sel && { cx: sel.x + 0.5, cy: sel.y + 0.5, r });
  const f = state.splitFrom;
  const end = to ?? f;
  put(from, f && { cx: f[0] + 0.5, cy: f[1] + 0.5, r: r / 2 });
  put(line, f && { x1: f[0] + 0.5, y1: f[1] + 0.5, x2: end[0] + 0.5, y2: end[1] + 0.5 });
  svg.dataset.split = f ? 'drawing' : '';
}

export function editPointerDown(e) {
  const cell = cellFromEvent(e);
  if (state.editMode === 'merge' && state.selected) {
    const { x, y } = state.selected;
    setEditMode(null);
    addEdit({ op: 'merge', at: [[x, y], cell] });
  } else if (state.editMode === 'split') {
    e.preventDefault();
    if (state.splitFrom) {
      finishSplit(cell);
      return;
    }
    ui.canvas.setPointerCapture?.(e.pointerId);
    state.splitFrom = cell;
    state.splitDrag = true;
    drawOverlay();
  } else {
    select({ x: cell[0], y: cell[1] });
  }
}

export function editPointerMove(e) {
  drawOverlay(cellFromEvent(e));
}

/** A drag ends the line where it is let go; a click leaves the first point for a second click. */
export function editPointerUp(e) {
  state.splitDrag = false;
  const cell = cellFromEvent(e);
  if (cell[0] !== state.splitFrom[0] || cell[1] !== state.splitFrom[1]) finishSplit(cell);
}

function finishSplit(to) {
  const from = state.splitFrom;
  setEditMode(null);
  addEdit({ op: 'split', line: [from, to] });
}

/** Merge… finished from the keyboard: the selected room with Rooms row `id` (a cell inside it). */
async function mergeWithRoom(id) {
  const { x, y } = state.selected;
  setEditMode(null);
  try {
    const other = await state.chain.call('roomAt', { id });
    if (other) await addEdit({ op: 'merge', at: [[x, y], [other.x, other.y]] });
  } catch (err) {
    showError(err);
  }
}

async function importEdits(file) {
  const list = parseEdits(await file.text());
  if (list instanceof Error) {
    showError(list);
    return;
  }
  await sendEdits(list, `Imported ${list.length} edit${list.length === 1 ? '' : 's'} from ${file.name}.`);
}

export function wireEdits() {
  const ed = ui.edit;
  const point = () => [state.selected.x, state.selected.y];
  ed.typeApply.addEventListener('click', () => addEdit({ op: 'type', at: point(), type: ed.type.value }));
  ed.nameForm.addEventListener('submit', (e) => {
    e.preventDefault();
    const name = ed.name.value.trim();
    if (!name) showError(new Error('Type a name for the room first.'));
    else if (state.selected?.room) addEdit({ op: 'name', at: point(), name });
  });
  ed.merge.addEventListener('click', () => setEditMode(state.editMode === 'merge' ? null : 'merge'));
  ed.split.addEventListener('click', () => setEditMode(state.editMode === 'split' ? null : 'split'));
  ed.undo.addEventListener('click', undoEdit);
  ed.clear.addEventListener('click', () => sendEdits([], 'Cleared the edits.'));
  ed.exportEdits.addEventListener('click', () => save('edits.json', `${JSON.stringify(state.edits, null, 2)}\n`, 'application/json'));
  ed.importEdits.addEventListener('change', async () => {
    const [file] = ed.importEdits.files;
    ed.importEdits.value = '';
    if (file) await importEdits(file).catch(showError);
  });
  const pick = (e) => {
    const tr = e.target.closest('tr[data-room]');
    if (!tr || !state.stats) return;
    if (e.type === 'keydown' && e.key !== 'Enter' && e.key !== ' ') return;
    e.preventDefault();
    const id = Number(tr.dataset.room);
    if (state.editMode === 'merge' && state.selected) mergeWithRoom(id);
    else select({ id });
  };
  ui.rooms.addEventListener('click', pick);
  ui.rooms.addEventListener('keydown', pick);
}
