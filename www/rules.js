// The rules editor: edit the knowledge base that supervises the floor-plan chain, see where it
// is wrong, what evidence the chain's best world gives and what the rules infer from it, and
// restart the chain with the edited rules. The engine is the library's (pkg/ksmcmc.js); this
// file is wiring.

import init, { Map as OccMap, Mapper, builtinIndoorRules, checkRules, drawMapper, inferWorld } from './pkg/ksmcmc.js';
import { messages } from './lib/messages.js';
import { rulesEditor } from './lib/rules-editor.js';
import { naturalCompare } from './lib/natural.js';

const SAMPLE = 'office-small';
const BUDGET_MS = 12;
const INFER_EVERY_MS = 400;

const $ = (id) => document.getElementById(id);
const { showError } = messages({ message: $('message'), messageText: $('message-text') });
const ui = { kb: $('kb'), error: $('kb-error'), map: $('map'), evidence: $('evidence'), marginals: $('marginals').tBodies[0], sale: $('salele').tBodies[0] };

const state = { editor: null, map: null, resolution: 0.05, mapper: null, goodKb: '', kbUsed: '', error: null, runs: 0, lastInfer: 0, inferred: null, worldUnits: 0, inferError: null };

/** A good text becomes the knowledge base; a bad one is reported and the last good one stays. */
function checked(text, err) {
  state.error = err;
  if (!err) state.goodKb = text;
}

function run() {
  state.mapper?.free();
  state.kbUsed = state.goodKb;
  state.mapper = new Mapper(state.map, JSON.stringify({ knowledge: { enabled: true, kb: state.kbUsed } }), 1);
  state.runs++;
  state.inferred = null;
  state.lastInfer = 0;
  $('runs').textContent = String(state.runs);
}

function cell(tr, text) {
  const td = document.createElement('td');
  td.textContent = text;
  tr.append(td);
}

function infer() {
  const world = state.mapper.bestWorldJson();
  state.worldUnits = JSON.parse(world).units.length;
  try {
    state.inferred = JSON.parse(inferWorld(state.kbUsed, world, state.resolution));
    state.inferError = null;
  } catch (e) {
    state.inferError = String(e.message ?? e);
    return;
  }
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

function frame(now) {
  try {
    state.mapper.runFor(BUDGET_MS);
    $('iteration').textContent = String(state.mapper.iteration);
    $('units').textContent = String(state.mapper.bestUnits);
    if (now - state.lastInfer > INFER_EVERY_MS) {
      state.lastInfer = now;
      infer();
      drawMapper(ui.map, state.mapper, { show: 'best', scale: 2 });
    }
  } catch (e) {
    showError(e);
  }
  requestAnimationFrame(frame);
}

async function main() {
  try {
    await init();
    const get = async (file) => {
      const r = await fetch(`samples/${SAMPLE}/${file}`);
      if (!r.ok) throw new Error(`samples/${SAMPLE}/${file}: ${r.status}`);
      return r;
    };
    const yaml = await (await get('map.yaml')).text();
    const pgm = new Uint8Array(await (await get('map.pgm')).arrayBuffer());
    state.map = OccMap.fromYaml(yaml, pgm);
    state.resolution = Number(yaml.match(/resolution:\s*([0-9.eE+-]+)/)?.[1] ?? 0.05);
    ui.kb.value = builtinIndoorRules();
    state.editor = rulesEditor(ui.kb, { check: checkRules, status: ui.error, okText: 'Knowledge base OK', gutterId: 'gutter', onCheck: checked });
    $('rerun').addEventListener('click', run);
    $('builtin').addEventListener('click', () => {
      ui.kb.value = builtinIndoorRules();
      state.editor.check();
    });
    run();
    window.__rules = {
      snapshot: () => ({
        runs: state.runs,
        iteration: state.mapper?.iteration ?? 0,
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
      }),
    };
    document.documentElement.dataset.state = 'ready';
    requestAnimationFrame(frame);
  } catch (e) {
    document.documentElement.dataset.state = 'error';
    showError(e);
  }
}
main();
