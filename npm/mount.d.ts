// Types of mount.js: a live-mapper widget for documentation pages.

import type { Map as OccupancyMap, Mapper } from './ksmcmc.js';
import type { SAMPLES } from './samples.js';

export { SAMPLES } from './samples.js';

/** A sample name: office-small, office-rotated, furnished, partial, two-corridors, building-large, two-wings. */
export type SampleName = keyof typeof SAMPLES;

export interface MountOptions {
  /** A built-in sample, remade by the synthetic generator (default 'office-small'). */
  sample?: SampleName;
  /** Your own map: a `Map`, the bytes of a PGM or PNG, or a ROS pair `{ yaml, image }`. */
  map?: OccupancyMap | Uint8Array | ArrayBuffer | { yaml: string; image: Uint8Array | ArrayBuffer };
  /** A map to fetch: a PGM or PNG, or a map.yaml (its image is fetched relative to it). */
  url?: string | URL;
  /**
   * How a map read from a file (`map` bytes or `{ yaml, image }`, or `url`) is classified:
   * `'auto'` (default) finds the background grays from the histogram, as `ksmcmc floorplan`
   * reads every format, so a PNG, a PGM and a map.yaml of the same pixels give the same cells
   * (a YAML with `negate: 1` or `mode: raw` keeps its own rule); `'fixed'` uses the default
   * intensity thresholds (`Map.fromBytes`) or the map.yaml's own.
   */
  classify?: 'auto' | 'fixed';
  /** The chain's seed, a whole number >= 0 (default 1): the same seed gives the same chain. */
  seed?: number | bigint;
  /** Chain settings: a JSON object (or its text) of any subset of `chainConfigDefaults()`. */
  config?: string | Record<string, unknown>;
  /**
   * Knowledge supervision with the built-in indoor rules (default true, as `ksmcmc floorplan`);
   * false runs the weak prior (sets `knowledge.enabled` to false in `config`).
   */
  knowledge?: boolean;
  /**
   * Start running at once (default false). Honours `prefers-reduced-motion: reduce` by staying
   * paused; `'always'` starts regardless.
   */
  autoplay?: boolean | 'always';
  /**
   * Pause once the chain has settled (`Mapper.settledAt`: the best log posterior stopped
   * improving); Start runs on. Default: true for your own `map` or `url`, false for a sample.
   */
  stopWhenSettled?: boolean;
  /** Milliseconds of iterations per animation frame (default 8). */
  budgetMs?: number;
  /** A fixed number of iterations per frame instead of a time budget. */
  iterationsPerFrame?: number;
  /** Which world to draw: the chain's current one (default) or the best so far. */
  show?: 'current' | 'best';
  /** Overlay the posterior cloud (the last accepted worlds as thin lines; default false). */
  cloud?: boolean;
  /** Unit type and id labels on the map (default false). */
  labels?: boolean;
  /** Draw the scene graph beside the map (default true). */
  graph?: boolean;
  /** Show the buttons and switches (default true); without them only the statistics line. */
  controls?: boolean;
  /**
   * Explain a building whose walls run in several directions wing by wing once the chain
   * stops (paused, stepped or settled), as `ksmcmc floorplan` does: a chain per wing, turned by
   * its direction, with the chain's seed and iterations, stepped in slices of `budgetMs`; the
   * best-world view then shows their world (`stats().wings`). Loads the plan module
   * (`ksmcmc_plan.js`, beside `mount.js`). Default false.
   */
  wings?: boolean;
  /** Where ksmcmc_bg.wasm is, if not next to ksmcmc.js (passed to `init`). */
  wasm?: string | URL | Request | BufferSource | WebAssembly.Module;
  /** Called after every drawn frame. */
  onUpdate?: (stats: MapperStats) => void;
  /** Called when stepping or drawing fails (the widget pauses and shows the message). */
  onError?: (error: unknown) => void;
}

export interface MapperStats {
  iteration: number;
  logPosterior: number;
  bestLogPosterior: number;
  /** Acceptance rate over the recent proposals, 0 to 1. */
  acceptance: number;
  units: number;
  bestUnits: number;
  doors: number;
  /** K(W, M) of the current world (world frame). */
  predictionRate: number;
  /** K(W, M) of the best world on the map. */
  bestPredictionRate: number;
  /** Measured while running; 0 when paused. */
  iterationsPerSecond: number;
  /** The iteration at which the chain settled (`Mapper.settledAt`), or null. */
  settledAt: number | null;
  running: boolean;
  /**
   * With the option `wings`, once the wings are explained for this iteration: how many (0 for
   * a building of one direction, whose world is the chain's), the units of their world and its
   * K(W, M); null before.
   */
  wings: { count: number; units: number; predictionRate: number } | null;
}

export interface MapperWidget {
  /** The widget's root element (inside the element given to `mount`). */
  readonly element: HTMLElement;
  /**
   * The chain, for anything the widget does not show (`worldJson()`, `trace()`, ...; the best
   * world's rooms and exports: a `Plan` of `ksmcmc_plan.js` made from `mapper.planInput()`).
   */
  readonly mapper: Mapper;
  readonly running: boolean;
  play(): void;
  pause(): void;
  toggle(): void;
  /** Runs `n` iterations at once (default: iterationsPerFrame, or 500) and redraws. */
  step(n?: number): void;
  /** Starts over, with the same seed or another. */
  reset(seed?: number | bigint): void;
  stats(): MapperStats;
  redraw(): void;
  /**
   * The map's zoom (1: the whole map) and the point at the centre of the view, as fractions
   * of the map's width and height. Wheel, pinch, drag, the zoom buttons and, with the map
   * focused, + − 0 and the arrow keys change it.
   */
  readonly view: { zoom: number; cx: number; cy: number };
  /** Shows the whole map again. */
  resetView(): void;
  /** Stops the chain, removes the widget and frees its memory. */
  destroy(): void;
}

/**
 * Builds a live mapper inside `element`: the map with the chain's world, the scene graph,
 * Start/Pause (Space), Step (S) and Reset (R), and a statistics line. Rejects with an Error
 * for unknown options, an unknown sample, a map that cannot be loaded or explained, or a bad
 * config.
 */
export function mount(element: HTMLElement, options?: MountOptions): Promise<MapperWidget>;

/** Initialises the WebAssembly module once; `mount` calls it. */
export function ready(wasm?: MountOptions['wasm']): Promise<unknown>;

/**
 * A sample remade from its recipe: the same cells as samples/NAME/map.pgm. Loads the synthetic
 * generator's module (ksmcmc_synth.js, beside ksmcmc.js) the first time.
 */
export function loadSample(name: SampleName): Promise<OccupancyMap>;
