// The page's side of lib/chain-worker.js (and of lib/explore-worker.js, which answers the same
// way): requests as promises.

export class RemoteChain {
  /**
   * @param {(message: string, stats: object | null) => void} onError  called when the running
   *   chain fails (the worker has paused it)
   * @param {(stats: object) => void} onSettled  called when the worker paused the chain
   *   because it settled
   * @param {URL} [url]  the worker's module: lib/chain-worker.js, or one that answers the same
   *   way (lib/explore-worker.js)
   */
  constructor(onError, onSettled, url = new URL('./chain-worker.js', import.meta.url)) {
    this.worker = new Worker(url, { type: 'module' });
    this.pending = new Map();
    /**
     * Called with the chain's numbers while the worker explains the wings of a building whose
     * walls follow several directions (their `wings`), and once they are done (`wingsDone`).
     */
    this.onWings = null;
    this.next = 1;
    this.worker.onmessage = (e) => {
      const { id, result, error, event } = e.data;
      if (event === 'error') {
        onError(e.data.message, e.data.stats);
        return;
      }
      if (event === 'settled') {
        onSettled(e.data.stats);
        return;
      }
      if (event === 'wings') {
        this.onWings?.(e.data.stats);
        return;
      }
      const p = this.pending.get(id);
      if (!p) return;
      this.pending.delete(id);
      if (error !== undefined) p.reject(new Error(error));
      else p.resolve(result);
    };
    this.worker.onerror = (e) => {
      e.preventDefault?.();
      const err = new Error(`the chain's worker failed: ${e.message ?? 'it did not load'}`);
      for (const p of this.pending.values()) p.reject(err);
      this.pending.clear();
      onError(err.message, null);
    };
  }

  /** Sends a request at once (in the order of the calls) and resolves with the reply. */
  call(op, args = {}, transfer = []) {
    const id = this.next++;
    return new Promise((resolve, reject) => {
      this.pending.set(id, { resolve, reject });
      this.worker.postMessage({ id, op, args }, transfer);
    });
  }

  /** How many requests wait for their reply. */
  get busy() {
    return this.pending.size;
  }
}
