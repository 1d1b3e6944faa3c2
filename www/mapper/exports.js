// The live mapper's downloads: world.json, labels.pgm, the overlay PNG, the scene graph, the
// report, GeoJSON, SVG and world.glb, each made by the chain's worker from the best world (the
// plan module, lib/chain-worker.js), and edits.json (edits.js).

import { download } from '../lib/download.js';
import { attempt, say, state, ui } from './state.js';
import { invoke } from './chain.js';
import { heights } from './view.js';

export function save(name, data, type) {
  download(name, data, type);
  say(`Saved ${name}.`);
}

/** The export buttons: each downloads what the chain's worker makes of the best world. */
export function wireExports() {
  const ex = ui.exports;
  const exporter = (name, type, method, args = () => []) => () =>
    attempt(async () => save(name, await invoke(method, ...args()), type));
  ex.world.addEventListener('click', exporter('world.json', 'application/json', 'bestWorldJson'));
  ex.labels.addEventListener('click', exporter('labels.pgm', 'image/x-portable-graymap', 'labelsPgm'));
  ex.png.addEventListener('click', exporter('overlay.png', 'image/png', 'toPng', () => [{ show: state.show, cloud: state.cloud, labels: state.labels, unitLabels: state.unitLabels }]));
  ex.graph.addEventListener('click', exporter('graph.json', 'application/json', 'graphJson'));
  ex.report.addEventListener('click', exporter('report.json', 'application/json', 'reportJson'));
  ex.geojson.addEventListener('click', exporter('world.geojson', 'application/geo+json', 'geojson', () => (ui.georef.value.trim() ? [ui.georef.value.trim()] : [])));
  ex.svg.addEventListener('click', exporter('world.svg', 'image/svg+xml', 'svg'));
  ex.glb.addEventListener('click', exporter('world.glb', 'model/gltf-binary', 'worldGlb', () => [heights()]));
}
