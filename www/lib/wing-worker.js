// One wing's chain in a worker of its own (issue 36), so that the live mapper explains a
// building's wings side by side, as `ksmcmc floorplan` runs each wing's chain on a thread of
// its own: the wing's map, turned by the wing's direction, with the first chain's settings,
// seed and iterations (floorplan::wings). Started by wing-workers.js; it posts
// { iteration } as it goes and { input } (the chain's `planInput()`) at the end, or
// { error }. Nothing here draws or answers requests, so it runs in long steps.

import init, { Map as OccMap, Mapper } from '../pkg/ksmcmc.js';
import { wingChain } from './wing-chains.js';

/** Iterations between progress messages. */
const STEP = 2000;

const ready = init();

onmessage = async ({ data }) => {
  const { yaml, pgm, config, rotationDeg, seed, target } = data;
  try {
    await ready;
    const chain = wingChain({ Map: OccMap, Mapper, yaml, pgm, config, rotationDeg, seed });
    try {
      while (chain.iteration < target) {
        chain.step(Math.min(STEP, target - chain.iteration));
        postMessage({ iteration: chain.iteration });
      }
      postMessage({ input: chain.planInput() });
    } finally {
      chain.free();
    }
  } catch (err) {
    postMessage({ error: err instanceof Error ? err.message : String(err) });
  }
};
