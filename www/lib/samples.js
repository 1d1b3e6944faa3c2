// The sample maps under www/samples/NAME/ (map.yaml, map.pgm, truth.json, ...) and the sample
// list the live mapper and the Exploration page share: fetching a sample, and keeping the list
// and its description in step with the map on show.

/**
 * A file of sample `name`; throws, naming the file and the HTTP status, if it cannot be had.
 * @param {string} name
 * @param {string} file
 * @returns {Promise<Response>}
 */
export async function fetchSampleFile(name, file) {
  const r = await fetch(`samples/${name}/${file}`);
  if (!r.ok) throw new Error(`samples/${name}/${file}: ${r.status} ${r.statusText}`);
  return r;
}

/**
 * Sample `name`'s map as a map source ([`buildMap`](./map-source.js)): its map.yaml and map.pgm.
 * @param {string} name
 * @returns {Promise<{kind: 'yaml', yaml: string, image: Uint8Array}>}
 */
export async function fetchSampleMap(name) {
  const [yaml, pgm] = await Promise.all([
    fetchSampleFile(name, 'map.yaml').then((r) => r.text()),
    fetchSampleFile(name, 'map.pgm').then((r) => r.arrayBuffer()),
  ]);
  return { kind: 'yaml', yaml, image: new Uint8Array(pgm) };
}

/**
 * A sample list (a `<select>` of sample names) with the description of the picked one shown in
 * `hint`.
 */
export class SampleList {
  /**
   * @param {HTMLSelectElement} select
   * @param {HTMLElement} hint
   * @param {string} otherLabel the entry shown for a map that is no sample
   */
  constructor(select, hint, otherLabel) {
    this.select = select;
    this.hint = hint;
    this.otherLabel = otherLabel;
    /** @type {{name: string, description?: string}[]} */
    this.samples = [];
  }

  /**
   * Reads the list of samples (samples/index.json) into the `<select>`, enables it and picks
   * `wanted`, or the first sample when there is none of that name. Throws, with the HTTP
   * status, when the list cannot be had.
   * @param {string} wanted
   */
  async fill(wanted) {
    const r = await fetch('samples/index.json');
    if (!r.ok) throw new Error(`${r.status} ${r.statusText}`);
    this.samples = await r.json();
    for (const s of this.samples) this.select.append(new Option(`${s.name} (${s.width} × ${s.height})`, s.name));
    this.select.disabled = false;
    this.select.value = this.samples.some((s) => s.name === wanted) ? wanted : this.samples[0]?.name;
    this.describe();
  }

  /** Shows the picked sample's description. */
  describe() {
    this.hint.textContent = this.samples.find((s) => s.name === this.select.value)?.description ?? '';
  }

  /**
   * Shows `sample` as picked, or, for any other map (`null`), an entry saying so (disabled: it
   * cannot be picked, only left by picking a sample).
   * @param {string|null} sample
   */
  show(sample) {
    let other = this.select.querySelector('option[value=""]');
    if (sample) {
      other?.remove();
      this.select.value = sample;
    } else {
      if (!other) {
        other = new Option(this.otherLabel, '');
        other.disabled = true;
        this.select.prepend(other);
      }
      this.select.value = '';
    }
    this.describe();
  }

  /**
   * The sample named `name`; throws, saying what to do, for no name or an unknown one.
   * @param {string} name
   */
  find(name) {
    if (!name) throw new Error('Pick a sample from the list first.');
    const info = this.samples.find((s) => s.name === name);
    if (!info) throw new Error(`There is no sample "${name}".`);
    return info;
  }
}
