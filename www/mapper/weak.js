// The weak prior beside the chain (Compare with the weak prior): a second chain in its own
// worker, on the same map with the same seed and settings but knowledge supervision off, kept
// at the main chain's iteration, its picture drawn through the same view, and a caption under
// each picture saying what each chain has found. Its state is `state.weak` (null when off).

import { formatNumber } from '../lib/plot.js';
import { RemoteChain } from '../lib/remote-chain.js';
import { showError, state, ui } from './state.js';
import { schedule, withoutKnowledge } from './chain.js';
import { roomsByType, RoomsFeed } from './rooms.js';
import { fit } from './view.js';

/** The weak prior's chain catches up with the main one in steps of at most this many iterations. */
const WEAK_STEP_MAX = 20000;

/** Turns the comparison with the weak prior on or off (a second chain in its own worker). */
export function setCompare(on) {
  ui.compare.checked = on;
  if (on && !state.weak) {
    const weak = {
      chain: new RemoteChain((message) => showError(new Error(`The weak prior's chain: ${message}`)), () => {}),
      stats: null,
      picture: null,
      inFlight: false,
      redrawPending: false,
      /** Counts the weak chain's restarts: replies about an older one are dropped. */
      token: 0,
    };
    weak.rooms = new RoomsFeed(() => weak.chain, () => updateSides());
    state.weak = weak;
    startWeak();
  } else if (!on && state.weak) {
    state.weak.chain.worker.terminate();
    state.weak.picture?.close();
    state.weak = null;
    state.weakShown?.close();
    state.weakShown = null;
  }
  ui.weakFigure.hidden = !on;
  ui.mainCaption.hidden = !on;
  // The two pictures take the width of the page; the scene graph and the plots go below.
  ui.stage.closest('.mapper-grid').classList.toggle('comparing', on);
  fit();
  updateSides();
}

/**
 * Starts the weak prior's chain over on the main chain's map with its seed and settings, but
 * knowledge supervision off; it then follows the main chain's iterations.
 */
export async function startWeak() {
  const weak = state.weak;
  if (!weak || !state.source || !state.args) return;
  const token = ++weak.token;
  weak.stats = null;
  weak.picture?.close();
  weak.picture = null;
  const { seed, config } = state.args;
  try {
    const { stats } = await weak.chain.call('load', { source: state.source, config: withoutKnowledge(config ?? '') || undefined, seed });
    if (state.weak !== weak || token !== weak.token) return;
    weak.stats = stats;
    weak.rooms.restart(stats.generation, stats.iteration);
    weak.redrawPending = true;
    schedule();
  } catch (err) {
    if (state.weak === weak && token === weak.token) showError(new Error(`The weak prior's chain did not start: ${err.message}`));
  }
}

/** What the weak prior's worker draws: the main view (a reference world it does not have: its best). */
function weakView(generation) {
  return {
    generation,
    show: state.show === 'reference' ? 'best' : state.show,
    cloud: state.cloud,
    labels: state.labels,
    unitLabels: state.unitLabels,
    legend: false,
    scale: state.drawScale,
    graphWidth: 80,
    graphHeight: 60,
    graphShow: 'best',
    traceFrom: Infinity,
  };
}

/**
 * Steps the weak prior's chain towards the main chain's iteration (at most WEAK_STEP_MAX at a
 * time) and asks for its picture; one request at a time, in its own worker, so the page waits
 * for nothing.
 */
export function advanceWeak() {
  const weak = state.weak;
  if (!weak || !weak.stats || weak.inFlight || !state.stats) return;
  const behind = state.stats.iteration - weak.stats.iteration;
  if (behind <= 0 && !weak.redrawPending) return;
  weak.inFlight = true;
  weak.redrawPending = false;
  const token = weak.token;
  const steps = behind > 0 ? weak.chain.call('step', { n: Math.min(WEAK_STEP_MAX, behind) }) : null;
  const picture = weak.chain.call('frame', weakView(weak.stats.generation));
  Promise.all([steps, picture]).then(
    ([, result]) => {
      weak.inFlight = false;
      result?.graph.close();
      if (state.weak !== weak || token !== weak.token || !result) {
        result?.picture.close();
      } else {
        weak.picture?.close();
        weak.picture = result.picture;
        weak.stats = result.stats;
      }
      schedule();
    },
    (err) => {
      weak.inFlight = false;
      if (state.weak === weak && token === weak.token) showError(new Error(`The weak prior's chain: ${err.message}`));
    },
  );
}

/** A side's summary: K(W,M), units, rooms and rooms by type. */
function sideText(stats, rooms) {
  if (!stats) return 'starting…';
  const parts = [`K(W,M) ${formatNumber(stats.bestPredictionRate, 4)}`, `${stats.bestUnits} units`];
  parts.push(rooms ? `${rooms.length} rooms${rooms.length ? ` (${roomsByType(rooms)})` : ''}` : 'rooms …');
  return `iteration ${formatNumber(stats.iteration)} · ${parts.join(' · ')}`;
}

/** The captions of the two pictures when the weak prior is shown beside the main chain. */
export function updateSides() {
  const weak = state.weak;
  if (!weak) return;
  ui.mainTitle.textContent = state.args?.knowledge === false ? 'This chain (knowledge supervision off)' : 'Knowledge';
  ui.mainSide.textContent = sideText(state.stats, state.rooms.rooms);
  ui.weakSide.textContent = sideText(weak.stats, weak.rooms.rooms);
  ui.weakCanvas.setAttribute('aria-label', `The weak prior's chain: ${ui.weakSide.textContent}`);
}
