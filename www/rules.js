// The rules editor: edit the knowledge base that supervises the floor-plan chain, see where it
// is wrong, what evidence the chain's best world gives and what the rules infer from it, and
// restart the chain with the edited rules. The engine is the library's (pkg/ksmcmc_rules.js
// here and for the inference, the chain's pkg/ksmcmc.js in the worker); this file is wiring. The chain and the inference run in a Web Worker (lib/chain-worker.js), as on
// the live mapper page, so that neither blocks a frame of the page.

import init, {
  builtinFrontierRules, builtinIndoorRules, checkFrontierRules, checkRules, handSetFrontierRules, handSetIndoorRules,
} from './pkg/ksmcmc_rules.js';
import { messages } from './lib/messages.js';
import { RemoteChain } from './lib/remote-chain.js';
import { rulesEditor } from './lib/rules-editor.js';
import { naturalCompare } from './lib/natural.js';

/** The sample the chain explains: `?sample=NAME` (a folder of www/samples), else office-small. */
const SAMPLE = (() => {
  const asked = new URLSearchParams(location.search).get('sample');
  return asked && /^[a-z0-9-]+$/.test(asked) ? asked : 'office-small';
})();
const INFER_EVERY_MS = 400;

const $ = (id) => document.getElementById(id);
const { showError } = messages({ message: $('message'), messageText: $('message-text'), messageClose: $('message-close') });
const ui = {
  kb: $('kb'), error: $('kb-error'), map: $('map'), evidence: $('evidence'), marginals: $('marginals').tBodies[0], sale: $('salele').tBodies[0],
  frontier: $('frontier-kb'), frontierError: $('frontier-error'), placeholders: $('placeholders').tBodies[0], placeholdersSummary: $('placeholders-summary'),
};

const state = {
  editor: null, source: null, resolution: 0.05, chain: null, generation: -1, stats: null, busy: false,
  goodKb: '', kbUsed: '', error: null, runs: 0, lastInfer: 0, inferred: null, worldUnits: 0, inferError: null,
  /** The reference world to learn from (world.json text) and its name; learnings done. */
  reference: null, referenceName: '', learning: false, learned: 0,
  /** The frontier rules' editor, its last good text and the text the chain runs with, and its error. */
  frontierEditor: null, goodFrontier: '', frontierUsed: '', frontierError: null,
  /** The best world's placeholders as last read (null: none read yet). */
  placeholders: null,
};

const TYPES = new Set(['room', 'corridor', 'hall', 'other']);

/**
 * Puts `text` into the editor as an edit of the user's (so Ctrl+Z in the editor brings the old
 * text back), and checks it.
 */
function replaceRules(text, area = ui.kb, editor = state.editor) {
  const back = document.activeElement;
  area.focus();
  area.select();
  // insertText keeps the browser's undo history; where it is missing, the text is set.
  if (!document.execCommand?.('insertText', false, text) || area.value !== text) area.value = text;
  editor.check();
  area.setSelectionRange(0, 0);
  area.scrollTop = 0;
  if (back instanceof HTMLElement && back !== document.body) back.focus();
}

/** The same for the frontier rules' editor. */
const replaceFrontierRules = (text) => replaceRules(text, ui.frontier, state.frontierEditor);

/** Takes `text` as the reference world to learn from, if it parses and has typed units. */
function setReference(text, name) {
  let world;
  try {
    world = JSON.parse(text);
  } catch (e) {
    throw new Error(`${name} is not JSON: ${e.message}`);
  }
  const units = Array.isArray(world?.units) ? world.units : null;
  if (!units) throw new Error(`${name} is not a world.json: it has no units.`);
  const typed = units.filter((u) => TYPES.has(u.type)).length;
  if (typed === 0) throw new Error(`${name} has no typed units (room, corridor, hall or other) to learn from.`);
  state.reference = text;
  state.referenceName = name;
  $('learn').disabled = false;
  $('reference').textContent = `Reference world: ${name}, ${units.length} units, ${typed} of them typed.`;
}

/** Learns the editor's rules' weights from the reference world (in the worker) into the editor. */
async function learn() {
  if (!state.reference || state.learning) return;
  const rules = ui.kb.value;
  state.learning = true;
  $('learn').disabled = true;
  $('reference').textContent = `Learning from ${state.referenceName}…`;
  try {
    const learned = await state.chain.call('learn', { kb: rules, world: state.reference, resolution: state.resolution });
    replaceRules(learned);
    state.learned++;
    $('reference').textContent = `Learned the weights from ${state.referenceName}: they are in the editor (Ctrl+Z there undoes). Re-run the chain to use them.`;
  } catch (e) {
    $('reference').textContent = `Learning from ${state.referenceName} failed.`;
    showError(e);
  } finally {
    state.learning = false;
    $('learn').disabled = !state.reference;
  }
}

/**
 * The built-in rules as a person reads them: learned weights to three decimals (the file,
 * samples/knowledge/indoor-learned.mln, keeps them to the last bit, and the command line
 * reads the file), and the list of training files, paths of the build that learned them,
 * said in words.
 */
function forReading(text) {
  return text
    .split('\n')
    .map((line) => {
      if (/^\/\/ Training worlds \(\d+\):/.test(line)) {
        const n = line.match(/\((\d+)\)/)[1];
        return `// Training worlds (${n}): generated floors, samples/knowledge/learn-indoor.sh makes them.`;
      }
      return line.replace(/^(-?\d+\.\d{4,})(?=\s)/, (w) => String(Number(Number(w).toFixed(3))));
    })
    .join('\n');
}

/** A good text becomes the knowledge base; a bad one is reported and the last good one stays. */
function checked(text, err) {
  state.error = err;
  if (!err) state.goodKb = text;
}

/** Starts the chain over with the last good rules (in the worker; the numbers follow). */
async function run() {
  state.kbUsed = state.goodKb;
  state.frontierUsed = state.goodFrontier;
  state.placeholders = null;
  state.runs++;
  const runs = state.runs;
  state.inferred = null;
  state.stats = null;
  state.generation = -1;
  state.lastInfer = 0;
  $('runs').textContent = String(state.runs);
  try {
    const config = JSON.stringify({ knowledge: { enabled: true, kb: state.kbUsed, frontier_kb: state.frontierUsed } });
    const { stats } = await state.chain.call('load', { source: state.source, config, seed: 1 });
    if (runs !== state.runs) return;
    state.generation = stats.generation;
    state.stats = stats;
    await state.chain.call('play', { ipf: 'auto' });
  } catch (e) {
    showError(e);
  }
}

function cell(tr, text) {
  const td = document.createElement('td');
  td.textContent = text;
  tr.append(td);
}

/** Shows what the rules infer from the chain's best world (as the worker computed it). */
function showInferred({ world, inferred, error }) {
  state.worldUnits = JSON.parse(world).units.length;
  if (error !== null) {
    state.inferError = error;
    return;
  }
  state.inferred = JSON.parse(inferred);
  state.inferError = null;
  const inf = state.inferred;
  ui.evidence.textContent = inf.evidence.filter((f) => f.value).map((f) => `${f.predicate}(${f.args.join(',')})`).join('  ') || '(none)';
  ui.marginals.replaceChildren(
    ...Object.entries(inf.types).sort(([a], [b]) => naturalCompare(a, b)).map(([u, t]) => {
      const tr = document.createElement('tr');
      tr.dataset.unit = u;
      cell(tr, u);
      for (const p of [t.room, t.corr, t.hall, t.other]) cell(tr, p.toFixed(3));
      cell(tr, t.kind);
      return tr;
    }),
  );
  ui.sale.replaceChildren(
    ...inf.sameLength.map((s) => {
      const tr = document.createElement('tr');
      cell(tr, s.p);
      cell(tr, s.q);
      cell(tr, s.probability.toFixed(3));
      return tr;
    }),
  );
}

/** Lists the best world's placeholders (`placeholdersJson` text): what the frontier rules say. */
function showPlaceholders(text) {
  const list = JSON.parse(text);
  state.placeholders = list;
  const likely = list.filter((p) => p.p_new_room >= 0.5).length;
  ui.placeholdersSummary.textContent = list.length
    ? `${list.length} placeholder${list.length === 1 ? '' : 's'}, ${likely} likely to lead to a new room (P ≥ 0.5).`
    : 'The best world has no placeholders: no frontier between seen and unseen floor.';
  ui.placeholders.replaceChildren(
    ...list.map((p) => {
      const tr = document.createElement('tr');
      tr.dataset.placeholder = String(p.id);
      cell(tr, `#${p.id}`);
      cell(tr, p.room ? String(p.room) : '–');
      cell(tr, p.width_m.toFixed(2));
      cell(tr, p.p_new_room.toFixed(3));
      // The likeliest type in the table; all four in the row's title (phones have no room for
      // four more columns).
      const [kind, prob] = Object.entries(p.types).reduce((a, b) => (b[1] > a[1] ? b : a));
      cell(tr, `${kind} ${prob.toFixed(2)}`);
      tr.title = Object.entries(p.types).map(([k, v]) => `${k} ${v.toFixed(3)}`).join(', ');
      return tr;
    }),
  );
}

/** Every INFER_EVERY_MS: the best world's picture and inference from the worker. */
async function refresh() {
  const { generation, runs } = state;
  const view = { generation, show: 'best', cloud: false, labels: true, scale: 2, graphWidth: 80, graphHeight: 60, graphShow: 'best', traceFrom: Infinity };
  const [frame, inferred] = await Promise.all([
    state.chain.call('frame', view),
    state.chain.call('infer', { kb: state.kbUsed, resolution: state.resolution }),
  ]);
  frame?.graph.close();
  if (!frame || runs !== state.runs || generation !== state.generation || inferred.generation !== generation) {
    frame?.picture.close();
    return;
  }
  state.stats = frame.stats;
  $('iteration').textContent = String(frame.stats.iteration);
  $('units').textContent = String(frame.stats.bestUnits);
  const c = ui.map;
  if (c.width !== frame.picture.width || c.height !== frame.picture.height) {
    c.width = frame.picture.width;
    c.height = frame.picture.height;
  }
  c.getContext('2d').drawImage(frame.picture, 0, 0);
  frame.picture.close();
  showInferred(inferred);
  if (frame.stats.bestUnits > 0) {
    const text = await state.chain.call('invoke', { name: 'placeholdersJson' });
    if (runs === state.runs && generation === state.generation) showPlaceholders(text);
  }
}

function frame(now) {
  if (!state.busy && state.stats && now - state.lastInfer > INFER_EVERY_MS) {
    state.lastInfer = now;
    state.busy = true;
    refresh()
      .catch(showError)
      .finally(() => {
        state.busy = false;
      });
  }
  requestAnimationFrame(frame);
}

/** Fetches `file` of the sample; throws when it is not there. */
async function sampleFile(file) {
  const r = await fetch(`samples/${SAMPLE}/${file}`);
  if (!r.ok) throw new Error(`samples/${SAMPLE}/${file}: ${r.status}`);
  return r;
}

/** The two editors, with the built-in rules in them: the knowledge base's and the frontier rules'. */
function makeEditors() {
  ui.kb.value = forReading(builtinIndoorRules());
  state.editor = rulesEditor(ui.kb, { check: checkRules, status: ui.error, okText: 'Knowledge base OK', gutterId: 'gutter', onCheck: checked });
  ui.frontier.value = builtinFrontierRules();
  state.frontierEditor = rulesEditor(ui.frontier, {
    check: checkFrontierRules, status: ui.frontierError, okText: 'Frontier rules OK', gutterId: 'frontier-gutter',
    onCheck: (text, err) => {
      state.frontierError = err;
      if (!err) state.goodFrontier = text;
    },
  });
}

/** The sample's truth.json becomes the reference world. */
async function loadTruth() {
  try {
    const r = await sampleFile('truth.json');
    setReference(await r.text(), `${SAMPLE}/truth.json`);
  } catch (e) {
    showError(e);
  }
}

/** The world file picked becomes the reference world (the input is cleared to pick it again). */
async function pickReference(e) {
  const file = e.target.files[0];
  e.target.value = '';
  if (!file) return;
  try {
    setReference(await file.text(), file.name);
  } catch (err) {
    showError(err);
  }
}

/** The buttons: rules into the editors, re-running the chain, the reference world and learning. */
function wireButtons() {
  $('frontier-builtin').addEventListener('click', () => replaceFrontierRules(builtinFrontierRules()));
  $('frontier-handset').addEventListener('click', () => replaceFrontierRules(handSetFrontierRules()));
  $('truth').textContent = `Load ${SAMPLE}'s truth.json`;
  $('rerun').addEventListener('click', () => run());
  $('builtin').addEventListener('click', () => replaceRules(forReading(builtinIndoorRules())));
  $('handset').addEventListener('click', () => replaceRules(handSetIndoorRules()));
  $('learn').addEventListener('click', () => learn());
  $('truth').addEventListener('click', () => loadTruth());
  $('world-file').addEventListener('change', (e) => pickReference(e));
}

/** For the tests (tests/e2e/rules.test.mjs): the page's numbers as `window.__rules.snapshot()`. */
function snapshot() {
  return {
    runs: state.runs,
    iteration: state.stats?.iteration ?? 0,
    error: state.error,
    goodKb: state.goodKb,
    kbUsed: state.kbUsed,
    worldUnits: state.worldUnits,
    inferred: state.inferred,
    inferError: state.inferError,
    rows: ui.marginals.rows.length,
    badGutterLine: Number(document.querySelector('#gutter .bad')?.textContent ?? 0),
    underlined: document.querySelector('.rules-marks .err')?.textContent ?? null,
    errorText: ui.error.textContent,
    reference: state.referenceName,
    learning: state.learning,
    learned: state.learned,
    frontierError: state.frontierError,
    goodFrontier: state.goodFrontier,
    frontierUsed: state.frontierUsed,
    frontierErrorText: ui.frontierError.textContent,
    placeholders: state.placeholders,
    placeholderRows: ui.placeholders.rows.length,
  };
}

async function main() {
  try {
    await init();
    const yaml = await (await sampleFile('map.yaml')).text();
    const pgm = new Uint8Array(await (await sampleFile('map.pgm')).arrayBuffer());
    state.source = { kind: 'yaml', yaml, image: pgm };
    state.chain = new RemoteChain(showError, () => {});
    state.resolution = Number(yaml.match(/resolution:\s*([0-9.eE+-]+)/)?.[1] ?? 0.05);
    makeEditors();
    wireButtons();
    run();
    window.__rules = { snapshot };
    document.documentElement.dataset.state = 'ready';
    requestAnimationFrame(frame);
  } catch (e) {
    document.documentElement.dataset.state = 'error';
    showError(e);
  }
}
main();
