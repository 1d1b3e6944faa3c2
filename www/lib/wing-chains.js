// The chains of a building's wings (issue 13), as `ksmcmc floorplan` runs them: one per wing of
// a plan, on the wing's map, turned by the wing's direction, with the first chain's seed and
// iterations. Stepped in time slices with a pause between them, so that the `mount` embed draws
// frames meanwhile (the package ships this file beside mount.js); the wasm classes are passed
// in, since the embed imports the main module from its own place. The live mapper's worker
// runs them side by side in workers instead (wing-workers.js), each made by `wingChain` here.

/** Iterations of a wing's chain per slice, until the time of one is known. */
const FIRST_STEP = 200;

/**
 * The chain's settings (JSON text, empty for the defaults) as an object for its wings' chains,
 * or null when they fix the rotation (then one chain explains the map, as
 * `ksmcmc floorplan --rotation` does).
 * @param {string | undefined} text
 * @returns {object | null}
 */
export function wingSettings(text) {
  const c = text?.trim() ? JSON.parse(text) : {};
  return c.detectors?.rotation_deg != null ? null : c;
}

/**
 * A wing's chain: a `Mapper` on the wing's map (`pgm` with the floor's `yaml`), turned by the
 * wing's direction, with the first chain's settings and seed. The caller frees it.
 * @param {{ Map: Function, Mapper: Function, yaml: string, pgm: Uint8Array, config: object,
 *   rotationDeg: number, seed: number | bigint }} wing
 */
export function wingChain({ Map, Mapper, yaml, pgm, config, rotationDeg, seed }) {
  const map = Map.fromYaml(yaml, pgm);
  try {
    const detectors = { ...(config.detectors ?? {}), rotation_deg: rotationDeg };
    return new Mapper(map, JSON.stringify({ ...config, detectors }), seed);
  } finally {
    map.free();
  }
}

/**
 * Runs the chain of each wing of plan `first` (a `Plan` of ksmcmc_plan.js) until it has run
 * `target` iterations, in slices of about `sliceMs` with a macrotask between them, and returns
 * their plan inputs in order; null once `gone()` says the run is stale (checked after each
 * slice). `onProgress({ wing, of, iteration, rotationDeg })` is called as each wing's chain
 * starts (iteration 0) and after each slice.
 * @param {{ first: object, yaml: string, config: object, seed: number, target: number,
 *   sliceMs: number, Map: Function, Mapper: Function, gone: () => boolean,
 *   onProgress: (p: { wing: number, of: number, iteration: number, rotationDeg: number }) => void }} run
 * @returns {Promise<string[] | null>}
 */
export async function runWingChains({ first, yaml, config, seed, target, sliceMs, Map, Mapper, gone, onProgress }) {
  const of = first.wingCount;
  const inputs = [];
  let step = FIRST_STEP;
  for (let k = 0; k < of; k++) {
    const rotationDeg = first.wingRotationDeg(k);
    onProgress({ wing: k + 1, of, iteration: 0, rotationDeg });
    const chain = wingChain({ Map, Mapper, yaml, pgm: first.wingMapPgm(k), config, rotationDeg, seed });
    try {
      while (chain.iteration < target) {
        const t0 = performance.now();
        const n = Math.min(step, target - chain.iteration);
        chain.step(n);
        step = Math.max(16, Math.round((n * sliceMs) / Math.max(performance.now() - t0, 0.1)));
        onProgress({ wing: k + 1, of, iteration: chain.iteration, rotationDeg });
        await new Promise((resolve) => setTimeout(resolve, 0));
        if (gone()) return null;
      }
      inputs.push(chain.planInput());
    } finally {
      chain.free();
    }
  }
  return inputs;
}
