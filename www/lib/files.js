// Choosing what to load from the files a person picked: one map image, or a ROS map.yaml with
// the image it names. Pure functions on names and text; the page reads the bytes.

/** True for `.yaml` / `.yml` file names. */
export function isYamlName(name) {
  return /\.ya?ml$/i.test(name);
}

/**
 * The `image:` entry of a map.yaml, or null if it has none. Reads flat `key: value` lines as
 * map_server writes them, with comments and quotes; the library parses the rest.
 * @param {string} text
 * @returns {string|null}
 */
export function yamlImageName(text) {
  for (const raw of text.split(/\r?\n/)) {
    const m = /^\s*image\s*:\s*(.*)$/.exec(raw);
    if (!m) continue;
    let v = m[1].trim();
    if (v.startsWith('"') || v.startsWith("'")) {
      const end = v.indexOf(v[0], 1);
      v = end > 0 ? v.slice(1, end) : v.slice(1);
    } else {
      v = v.replace(/\s+#.*$/, '').trim();
    }
    return v === '' ? null : v;
  }
  return null;
}

/** The last path component, for `/` or `\` separators. */
export function baseName(path) {
  return path.split(/[\\/]/).pop();
}

/** A file name without its extension, for naming downloads. */
export function stem(name) {
  const b = baseName(name);
  const dot = b.lastIndexOf('.');
  return dot > 0 ? b.slice(0, dot) : b;
}

/**
 * The picked file that a map.yaml's `image:` names: same name, or same base name (the YAML may
 * give a path), or failing that the same base name ignoring case.
 * @param {string} imageRef
 * @param {string[]} names the names of the other picked files
 * @returns {string|null}
 */
export function matchImage(imageRef, names) {
  const want = baseName(imageRef);
  return (
    names.find((n) => n === imageRef) ??
    names.find((n) => baseName(n) === want) ??
    names.find((n) => baseName(n).toLowerCase() === want.toLowerCase()) ??
    null
  );
}

/**
 * Decides what to load from the picked file names.
 * @param {string[]} names
 * @returns {{kind: 'image', image: string} | {kind: 'yaml', yaml: string, images: string[]} | {kind: 'error', message: string}}
 */
export function planOpen(names) {
  const yamls = names.filter(isYamlName);
  const images = names.filter((n) => !isYamlName(n));
  if (names.length === 0) return { kind: 'error', message: 'No file was selected.' };
  if (yamls.length === 0) {
    if (images.length === 1) return { kind: 'image', image: images[0] };
    return {
      kind: 'error',
      message:
        `${images.length} images were selected (${images.join(', ')}); select one map image ` +
        '(PGM or PNG), or a map.yaml together with the image it names.',
    };
  }
  if (yamls.length > 1) {
    return { kind: 'error', message: `Select one map.yaml at a time, not ${yamls.length} (${yamls.join(', ')}).` };
  }
  return { kind: 'yaml', yaml: yamls[0], images };
}

/**
 * After reading the YAML: which image to load with it, or why none fits.
 * @param {string} yamlName
 * @param {string} yamlText
 * @param {string[]} images names of the other picked files
 * @returns {{image: string} | {message: string}}
 */
export function pickYamlImage(yamlName, yamlText, images) {
  const ref = yamlImageName(yamlText);
  if (ref === null) {
    return { message: `${yamlName} has no \`image:\` line naming the map image, so it is not a ROS map.yaml.` };
  }
  if (images.length === 0) {
    return {
      message:
        `${yamlName} names the image "${ref}": select it together with the YAML file ` +
        '(hold Ctrl or Shift in the file dialog to pick both).',
    };
  }
  const image = matchImage(ref, images);
  if (image === null) {
    return {
      message: `${yamlName} names the image "${ref}", but the selected image is ${images.map((n) => `"${n}"`).join(', ')}; select the image it names, or fix its \`image:\` line.`,
    };
  }
  return { image };
}

/**
 * Reads a seed typed by a person: a whole number, as a `number` when it is a safe integer and
 * as a `bigint` above that.
 * @param {string} text
 * @returns {number|bigint}
 */
export function parseSeed(text) {
  const t = String(text).trim();
  if (!/^\d+$/.test(t)) {
    throw new Error(`Seed: "${t}" is not a whole number; enter 0 or a positive whole number.`);
  }
  const big = BigInt(t);
  return big <= BigInt(Number.MAX_SAFE_INTEGER) ? Number(big) : big;
}

/**
 * Makes `stage` a drop target for files: it shows the `dragging` class while files hover
 * over it and calls `open(files)` with the dropped `FileList`.
 */
export function onDroppedFiles(stage, open) {
  for (const type of ['dragenter', 'dragover']) {
    stage.addEventListener(type, (e) => {
      e.preventDefault();
      stage.classList.add('dragging');
    });
  }
  stage.addEventListener('dragleave', (e) => {
    if (!stage.contains(e.relatedTarget)) stage.classList.remove('dragging');
  });
  stage.addEventListener('drop', (e) => {
    e.preventDefault();
    stage.classList.remove('dragging');
    open(e.dataTransfer.files);
  });
}

/**
 * The map in picked files, as a map source ([`buildMap`](./map-source.js)): one image (read
 * with the classification rule `classify`), or a map.yaml with the image it names. Throws,
 * saying what to pick, when the files are not one map.
 * @param {FileList|File[]} fileList
 * @param {string} classify 'auto' or 'fixed', for an image
 * @returns {Promise<{source: object, name: string, label: string}>}
 */
export async function readPickedMap(fileList, classify) {
  const files = [...fileList];
  const plan = planOpen(files.map((f) => f.name));
  if (plan.kind === 'error') throw new Error(plan.message);
  const byName = (n) => files.find((f) => f.name === n);
  if (plan.kind === 'image') {
    const file = byName(plan.image);
    const bytes = new Uint8Array(await file.arrayBuffer());
    return { source: { kind: 'image', bytes, classify }, name: stem(file.name), label: file.name };
  }
  const yaml = await byName(plan.yaml).text();
  const pick = pickYamlImage(plan.yaml, yaml, plan.images);
  if ('message' in pick) throw new Error(pick.message);
  const image = new Uint8Array(await byName(pick.image).arrayBuffer());
  return { source: { kind: 'yaml', yaml, image, classify }, name: stem(plan.yaml), label: `${plan.yaml} + ${pick.image}` };
}
