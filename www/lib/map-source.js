// Making a map from what a page read, the same in every worker: the page sends how to make it
// (a `source`: a map.yaml with its image, one image, or painted cell codes) and the worker
// builds the map with the library, so the bytes are parsed where the map is used. The worker
// hands in its module's `Map` class (ksmcmc.js for the live chain, ksmcmc_explore.js for the
// robot's): maps of one module cannot be used by another.

/**
 * The map a `source` describes, classified as the pages do: `{ kind: 'yaml', yaml, image,
 * classify }`, `{ kind: 'image', bytes, classify }` (`classify` 'auto' reclassifies by the
 * histogram, as `ksmcmc floorplan` does to every format) or `{ kind: 'cells', width, height, codes }`. Throws, saying why,
 * for bytes that are not a map. `OccMap` is the `Map` class of the caller's module.
 */
export function buildMap(source, OccMap) {
  switch (source.kind) {
    case 'yaml':
      return classified(OccMap.fromYaml(source.yaml, source.image), source.classify);
    case 'image':
      return classified(OccMap.fromBytes(source.bytes), source.classify);
    case 'cells':
      return OccMap.fromCells(source.width, source.height, source.codes);
    default:
      throw new Error(`unknown map source ${source.kind}`);
  }
}

/**
 * `map` as `classify` asks: 'auto' is the one rule `ksmcmc floorplan` reads every format by
 * (the same pixels give the same cells as a PNG, a PGM or a map.yaml); anything else keeps the
 * rule the map was read with (the default thresholds, or the map.yaml's own).
 */
function classified(map, classify) {
  if (classify !== 'auto') return map;
  try {
    return map.reclassify('auto');
  } finally {
    map.free();
  }
}
