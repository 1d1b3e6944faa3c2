// The chains of a building's wings side by side (issue 36): each wing's chain in a worker of
// its own (wing-worker.js), as many at once as the machine has cores (at most MAX_WORKERS),
// where wing-chains.js runs them one after another between frames. Each chain has its own seed
// and stream, so the plan inputs are the same whichever order and however many at once: byte
// for byte those of `ksmcmc floorplan --iterations N`.

/** The most wing chains run at once: each holds a copy of the map and its chain. */
const MAX_WORKERS = 4;

/** How many wing chains run at once on this machine for `wings` wings. */
export function wingWorkers(wings) {
  const cores = globalThis.navigator?.hardwareConcurrency || 2;
  return Math.max(1, Math.min(wings, cores, MAX_WORKERS));
}

/**
 * Runs the chain of each wing of plan `first` (a `Plan` of ksmcmc_plan.js) for `target`
 * iterations, side by side in workers, and returns their plan inputs in wing order; null once
 * `gone()` says the run is stale (checked at each progress message; the workers are then
 * stopped). `onProgress({ wing, of, iteration, rotationDeg, running })` tells of the first wing
 * not yet done: its iteration, and how many chains run at once.
 * @param {{ first: object, yaml: string, config: object, seed: number, target: number,
 *   gone: () => boolean, onProgress: (p: object) => void }} run
 * @returns {Promise<string[] | null>}
 */
export function runWingWorkers({ first, yaml, config, seed, target, gone, onProgress }) {
  const of = first.wingCount;
  const jobs = Array.from({ length: of }, (_, k) => ({ pgm: first.wingMapPgm(k), rotationDeg: first.wingRotationDeg(k) }));
  const inputs = new Array(of).fill(null);
  const iteration = new Array(of).fill(0);
  const workers = new Set();
  let next = 0;
  return new Promise((resolve, reject) => {
    let over = false;
    const stop = () => {
      over = true;
      for (const w of workers) w.terminate();
      workers.clear();
    };
    const progress = () => {
      const k = inputs.findIndex((input) => input === null);
      if (k >= 0) onProgress({ wing: k + 1, of, iteration: iteration[k], rotationDeg: jobs[k].rotationDeg, running: workers.size });
    };
    const start = () => {
      const k = next++;
      const w = new Worker(new URL('./wing-worker.js', import.meta.url), { type: 'module' });
      workers.add(w);
      w.onmessage = ({ data }) => {
        if (over) return;
        if (gone()) {
          stop();
          resolve(null);
        } else if (data.error !== undefined) {
          stop();
          reject(new Error(`wing ${k + 1} of ${of}: ${data.error}`));
        } else if (data.input !== undefined) {
          inputs[k] = data.input;
          w.terminate();
          workers.delete(w);
          if (next < of) start();
          if (inputs.every((input) => input !== null)) {
            over = true;
            resolve(inputs);
          } else progress();
        } else {
          iteration[k] = data.iteration;
          progress();
        }
      };
      w.onerror = (e) => {
        if (over) return;
        stop();
        reject(new Error(`wing ${k + 1} of ${of}: ${e.message ?? 'the worker failed'}`));
      };
      const { pgm, rotationDeg } = jobs[k];
      w.postMessage({ yaml, pgm, config, rotationDeg, seed, target });
    };
    if (of === 0) {
      resolve([]);
      return;
    }
    for (let i = wingWorkers(of); i > 0; i--) start();
    progress();
  });
}
