// The live mapper page's shared state: its elements (`ui`), its alert and status line, and the
// one `state` object every part of the page reads and changes. The page is split by concern
// (www/mapper.js wires it; www/mapper/: chain.js the chain in its worker, weak.js the weak
// prior beside it, view.js the canvas and its view, painting.js strokes on the map, rooms.js
// the Rooms table and the room pointed at, edits.js the person's corrections, exports.js the
// downloads, hooks.js the test hooks), and those modules keep no variables of their own: all
// the page holds is here, in one place, and the modules read and change it by name.
// The modules import each other's functions (an import circle among them is harmless: none
// calls another while it loads, only once the page runs); this one imports none of them.

import { brushOffsets } from '../lib/paint.js';
import { SampleList } from '../lib/samples.js';
import { messages } from '../lib/messages.js';

const $ = (id) => document.getElementById(id);
/** The page's elements, by what they are for (mapper.html gives their ids). */
export const ui = {
  message: $('message'), messageText: $('message-text'), messageClose: $('message-close'),
  status: $('status'), version: $('version'),
  run: $('run'), step: $('step'), reset: $('reset'), seed: $('seed'), ipf: $('ipf'),
  config: $('config'), configDefaults: $('config-defaults'), knowledge: $('knowledge'), stopSettled: $('stop-settled'),
  sampleForm: $('sample-form'), sample: $('sample'), sampleLoad: $('sample-load'), sampleHint: $('sample-hint'),
  file: $('file'), classify: $('classify'),
  paint: $('paint'), brush: $('brush'), brushValue: $('brush-value'),
  blankForm: $('blank-form'), blankWidth: $('blank-width'), blankHeight: $('blank-height'), blankCreate: $('blank-create'),
  showReference: $('show-reference'), cloud: $('cloud'), labels: $('labels'), unitLabels: $('unit-labels'), mapLegend: $('map-legend'),
  worldFile: $('world-file'), truth: $('truth'), referenceClear: $('reference-clear'),
  stage: $('stage'), canvas: $('map'), graph: $('graph'), mapName: $('map-name'), roomInfo: $('room-info'), zoomBar: $('zoom-bar'),
  compare: $('compare'), mainCaption: $('main-caption'), mainTitle: $('main-title'), mainSide: $('main-side'),
  weakFigure: $('weak-figure'), weakCanvas: $('weak-map'), weakSide: $('weak-side'),
  rooms: $('rooms').tBodies[0], roomsSummary: $('rooms-summary'),
  plotLp: $('plot-lp'), plotAcc: $('plot-acc'), plotLpValue: $('plot-lp-value'), plotAccValue: $('plot-acc-value'),
  stats: $('stats'),
  view3d: {
    toggle: $('view-3d'), panel: $('view3d-panel'), form: $('view3d-form'), canvas: $('view3d'),
    wall: $('wall-height'), door: $('door-height'), reset: $('view3d-reset'), status: $('view3d-status'),
  },
  route: {
    toggle: $('route-mode'), form: $('route-form'), from: $('route-from'), to: $('route-to'), plan: $('route-plan'),
    placeholder: $('route-placeholder'),
    layer: $('route-layer'), summary: $('route-summary'), rooms: $('route-rooms'), doors: $('route-doors'),
  },
  stat: {
    iteration: $('stat-iteration'), rate: $('stat-rate'), lp: $('stat-lp'), best: $('stat-best'), acc: $('stat-acc'),
    units: $('stat-units'), doors: $('stat-doors'), rooms: $('stat-rooms'), k: $('stat-k'), rotation: $('stat-rotation'), setup: $('stat-setup'),
    settled: $('stat-settled'),
  },
  exports: {
    world: $('export-world'), labels: $('export-labels'), png: $('export-png'), graph: $('export-graph'),
    report: $('export-report'), glb: $('export-glb'),
    geojson: $('export-geojson'), svg: $('export-svg'),
  },
  georef: $('georef'),
  edit: {
    selection: $('edit-selection'), type: $('edit-type'), typeApply: $('edit-type-apply'),
    nameForm: $('edit-name-form'), name: $('edit-name'), nameApply: $('edit-name-apply'),
    merge: $('edit-merge'), split: $('edit-split'), undo: $('edit-undo'), clear: $('edit-clear'),
    exportEdits: $('edit-export'), importEdits: $('edit-import'), list: $('edit-list'),
  },
};

/** The page's alert and status line (lib/messages.js), shared by every part of the page. */
export const { showError, clearError, say, attempt, loadWasm } = messages(ui);

/** Everything the page holds: the map, the chain's numbers and pictures, the view, the tools. */
export const state = {
  ready: false,
  /** The map being explained (a wasm Map on this thread: for painting and its size). */
  map: null,
  /** How the worker makes the map (what `load` was given): the weak prior's chain loads it too. */
  source: null,
  /** The best world's rooms, read from the worker (a RoomsFeed, made in main()). */
  rooms: null,
  /** Route mode: the ends picked and the route planned (a RouteView, made in main()). */
  route: null,
  /**
   * The 3D view: whether it is open, the View3d (made when first opened, when three.js
   * loads), the request on its way (a reply to an older one is dropped), its last error.
   */
  view3d: { open: false, view: null, token: 0, shown: 0, error: null },
  /** The weak prior's chain beside this one (Compare with the weak prior), or null. */
  weak: null,
  /** What the chain was started with (chainArgs()). */
  args: null,
  name: 'map',
  label: '',
  sample: null,
  /** The sample list, with the description of the picked sample. */
  sampleList: new SampleList(ui.sample, ui.sampleHint, '(an opened or painted map)'),
  /** The chain in its worker, and its numbers as last reported (null before the first map). */
  chain: null,
  stats: null,
  running: false,
  raf: 0,
  /** A picture is wanted (the view or the chain changed), one is on its way, one waits to be drawn. */
  redrawPending: false,
  inFlight: false,
  picture: null,
  ipf: 'auto',
  /** The best world first: its rooms are the plan's (issue 33); C shows the chain's current world. */
  show: 'best',
  cloud: false,
  labels: true,
  unitLabels: false,
  /** The reference world's text, kept to re-apply when the chain is rebuilt. */
  referenceJson: null,
  referenceName: '',
  /** The trace as read so far (plain arrays, appended to each frame). */
  trace: { iteration: [], logPosterior: [], acceptance: [] },
  initialLogPosterior: NaN,
  /** Pictures drawn while the chain ran, and when the rate was last measured: for iterations/s. */
  frames: 0,
  rate: { iteration: 0, time: 0, perSecond: 0 },
  /** Milliseconds drawing a picture takes on this thread (a running average). */
  drawMs: 0,
  scale: 1,
  /** Zoom and pan of the map (a Viewport, made in wire()); the weak prior's picture follows it. */
  viewport: null,
  /** Pixels per cell the worker draws at: `scale` at zoom 1, more when zoomed in. */
  drawScale: 1,
  /** The pictures last drawn, kept to draw them again when the view moves. */
  shown: null,
  weakShown: null,
  /** The painted cells while a stroke goes on (a canvas, one pixel per cell). */
  paintCanvas: null,
  /** The best world's rooms for pointing at (a RoomIndex), and the room shown: hovered, focused or pinned. */
  roomIndex: null,
  hover: { id: 0, pinned: false, anchor: null, mask: null },
  /** Where the mouse is over the map (client position), or null; whether the Rooms table is in use. */
  pointer: null,
  tableInUse: false,
  /** Painting: cell codes as loaded and as painted, the stroke's last cell. */
  painting: false,
  tool: 'occupied',
  brush: 3,
  offsets: brushOffsets(3),
  base: null,
  codes: null,
  strokeAt: null,
  strokeUndo: null,
  /** A picture of the painted cells is asked for at the next animation frame. */
  paintFramePending: false,
  /** The edits in force (as the worker's `editsJson` last said), the selected room's cell and id. */
  edits: [],
  selected: null,
  /** 'merge' or 'split' while the next click on the map finishes one; a split's first point. */
  editMode: null,
  splitFrom: null,
  splitDrag: false,
};
