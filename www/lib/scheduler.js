// The workers' time-sliced run loop, shared by lib/chain-worker.js and lib/explore-worker.js
// (both module workers, made by lib/remote-chain.js): a chain iterates for SLICE_MS, then the
// worker looks at the page's requests (among them the next picture), then the next slice. Each
// slice is a macrotask of its own, posted through a MessageChannel: setTimeout(0) would be
// clamped to 4 ms once nested, which would leave the chain idle a third of the time.

/** Milliseconds of iterations between looking at the page's requests. */
export const SLICE_MS = 8;

/**
 * Returns `schedule()`, which runs `loop` once at the next macrotask, however often it is
 * called before then. `loop` calls `schedule()` itself when it wants another slice.
 * @param {() => void} loop
 * @returns {() => void}
 */
export function scheduler(loop) {
  const tick = new MessageChannel();
  let scheduled = false;
  tick.port1.onmessage = () => {
    scheduled = false;
    loop();
  };
  return function schedule() {
    if (scheduled) return;
    scheduled = true;
    tick.port2.postMessage(0);
  };
}

/**
 * Whether work that takes turns with the chain is due again: a picture of the world, or a
 * request for its rooms. Such work takes at most `share` of the worker's time, so after a turn
 * that took `tookMs`, done at `doneAt` (performance.now()), the chain runs for
 * tookMs × (1 − share) / share before the next.
 */
export function turnDue(doneAt, tookMs, share) {
  return performance.now() - doneAt >= (tookMs * (1 - share)) / share;
}
