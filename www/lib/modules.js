// The package's other wasm modules (www/pkg/ksmcmc_plan.js, ksmcmc_rules.js, ...), imported
// and initialised when a worker first needs one, then kept; a failed import is tried again
// the next time.

const loaded = new Map();

/**
 * The initialised module `file` of www/pkg.
 * @param {string} file e.g. 'ksmcmc_plan.js'
 * @returns {Promise<object>}
 */
export function loadModule(file) {
  if (!loaded.has(file)) {
    const module = import(`../pkg/${file}`).then(
      async (m) => {
        await m.default();
        return m;
      },
      (err) => {
        loaded.delete(file);
        throw err;
      },
    );
    loaded.set(file, module);
  }
  return loaded.get(file);
}
