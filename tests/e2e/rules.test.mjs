// The rules editor (www/rules.html): the chain runs with the knowledge base, the page shows the
// best world's evidence and a marginals table with one row per unit, a syntax error is
// reported at its line and column while the last good rules stay, and re-running with edited
// rules restarts the chain and the inference with them.

import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import { openPage, startBrowser } from './harness.mjs';

let env;
before(async () => {
  env = await startBrowser();
});
after(async () => {
  await env?.close();
});

const snap = (page) => page.evaluate(() => window.__rules.snapshot());
const settled = (page) => page.evaluate(() => new Promise((ok) => requestAnimationFrame(() => requestAnimationFrame(ok))));
async function until(page, src, timeout = 60_000) {
  try {
    await page.waitForFunction(new Function(`const s = window.__rules.snapshot(); return ${src};`), null, { timeout });
  } catch (err) {
    const s = await snap(page);
    delete s.goodKb;
    delete s.kbUsed;
    assert.fail(`waited for ${src}: ${err.message.split('\n')[0]}; page at ${JSON.stringify(s).slice(0, 2000)}`);
  }
}

test('marginals table, syntax errors at line and column, re-run with edited rules', async () => {
  const page = await openPage(env, 'rules.html');
  const builtin = await page.inputValue('#kb');
  assert.match(builtin, /RoLi\(unit\)/);
  await until(page, 's.inferred && s.worldUnits >= 2 && s.rows === s.worldUnits');
  let s = await snap(page);
  assert.equal(s.runs, 1);
  assert.equal(Object.keys(s.inferred.types).length, s.worldUnits, 'one row per unit');
  const order = await page.$$eval('#marginals tbody tr', (rows) => rows.map((r) => Number(r.dataset.unit.replace(/\D/g, ''))));
  assert.deepEqual(order, [...order].sort((a, b) => a - b), `rows in the order of the unit numbers: ${order}`);
  assert.ok(s.inferred.evidence.some((f) => f.predicate === 'RoLi'), 'evidence has RoLi facts');
  assert.ok((await page.textContent('#evidence')).length > 0);
  for (const t of Object.values(s.inferred.types)) {
    for (const p of [t.room, t.corr, t.hall, t.other]) assert.ok(p >= 0 && p <= 1);
  }

  // A syntax error on a known line and column.
  const lines = builtin.split('\n');
  // The built-in rules are the learned ones: the weight is a number, with a `// was` comment.
  const i = lines.findIndex((l) => /^\S+ HaLi\(p\) => Hall\(p\)/.test(l));
  assert.ok(i >= 0, 'the built-in rules have HaLi(p) => Hall(p)');
  lines[i] = lines[i].replace('=> Hall(p)', '=> => Hall(p)');
  const col = lines[i].indexOf('=> Hall(p)') + 1;
  await page.fill('#kb', lines.join('\n'));
  await settled(page);
  s = await snap(page);
  assert.ok(s.error, 'the error is reported');
  assert.equal(s.error.line, i + 1);
  assert.equal(s.error.column, col);
  assert.equal(s.badGutterLine, i + 1, 'the gutter marks the line');
  assert.match(s.errorText, new RegExp(`^line ${i + 1}, column ${col}: `));
  assert.equal(s.underlined, '=>', 'the offending connective is underlined');
  // The underline sits on the text it names: on line i + 1, col - 1 characters in.
  const geo = await page.evaluate(() => {
    const ta = document.getElementById('kb');
    const mark = document.querySelector('.rules-marks .err');
    const cs = getComputedStyle(ta);
    const t = ta.getBoundingClientRect();
    const m = mark.getBoundingClientRect();
    return {
      top: m.top - (t.top + parseFloat(cs.paddingTop) - ta.scrollTop),
      left: m.left - (t.left + parseFloat(cs.paddingLeft) - ta.scrollLeft),
      line: parseFloat(cs.lineHeight),
      char: m.width / mark.textContent.length,
      decoration: getComputedStyle(mark).textDecorationStyle,
    };
  });
  assert.ok(Math.abs(geo.top / geo.line - i) < 0.3, `underline at line ${geo.top / geo.line + 1}, expected ${i + 1}`);
  assert.ok(Math.abs(geo.left / geo.char - (col - 1)) < 0.3, `underline at column ${geo.left / geo.char + 1}, expected ${col}`);
  assert.equal(geo.decoration, 'wavy');
  assert.equal(s.goodKb, builtin, 'the last good rules stay');
  // Re-running with an error uses the last good rules.
  await page.click('#rerun');
  s = await snap(page);
  assert.equal(s.runs, 2);
  assert.equal(s.kbUsed, builtin);

  // Edited rules: everything is a hall. Re-run, and the inference follows.
  const edited = `${builtin}\n20 Hall(p)\n`;
  await page.fill('#kb', edited);
  await settled(page);
  assert.equal((await snap(page)).error, null);
  await page.click('#rerun');
  s = await snap(page);
  assert.equal(s.runs, 3);
  assert.equal(s.kbUsed, edited);
  await until(page, 's.inferred && s.worldUnits >= 1 && s.rows === s.worldUnits');
  s = await snap(page);
  for (const [u, t] of Object.entries(s.inferred.types)) assert.ok(t.hall > 0.99, `${u}: ${JSON.stringify(t)}`);
  const kinds = await page.$$eval('#marginals tbody tr td:last-child', (tds) => tds.map((td) => td.textContent));
  assert.ok(kinds.length > 0 && kinds.every((k) => k === 'Hall'), `kinds ${kinds}`);
  assert.deepEqual(page.problems, []);
  await page.context().close();
});

test('learn the weights from the reference world, undo, hand-set weights, and the inference runs', async () => {
  const page = await openPage(env, 'rules.html');
  const builtin = await page.inputValue('#kb');
  assert.equal(await page.isDisabled('#learn'), true, 'nothing to learn from yet');
  await page.click('#truth');
  await page.waitForFunction(() => !document.getElementById('learn').disabled);
  assert.match(await page.textContent('#reference'), /office-small\/truth\.json, \d+ units, \d+ of them typed/);
  await page.click('#learn');
  await until(page, 's.learned === 1 && !s.learning');
  const learned = await page.inputValue('#kb');
  assert.match(learned, /\/\/ was /, 'the learned weights say what they were');
  assert.match(learned, /Weights learned in the rules editor/, 'learned here, not the built-in text');
  assert.notEqual(learned, builtin);
  let s = await snap(page);
  assert.equal(s.error, null, 'the learned rules parse');
  assert.equal(s.goodKb, learned);
  assert.match(await page.textContent('#reference'), /^Learned the weights from office-small\/truth\.json/);
  // Ctrl+Z in the editor brings the rules from before back.
  await page.focus('#kb');
  await page.keyboard.press('Control+z');
  await page.waitForFunction((b) => document.getElementById('kb').value === b, builtin);
  // The hand-set weights of Tab. 3.5.
  await page.click('#handset');
  const handset = await page.evaluate(async () => (await import('./pkg/ksmcmc_rules.js')).handSetIndoorRules());
  assert.equal(await page.inputValue('#kb'), handset);
  assert.notEqual(handset, builtin);
  // Learn again (from the hand-set rules) and run the chain and the inference with them.
  await page.click('#learn');
  await until(page, 's.learned === 2 && !s.learning');
  const relearned = await page.inputValue('#kb');
  assert.match(relearned, /\/\/ was /);
  assert.match(relearned, /Weights learned in the rules editor/);
  await settled(page);
  assert.equal((await snap(page)).error, null);
  await page.click('#rerun');
  s = await snap(page);
  assert.equal(s.runs, 2);
  assert.equal(s.kbUsed, relearned);
  await until(page, 's.inferred && s.worldUnits >= 2 && s.rows === s.worldUnits && s.inferError === null');
  s = await snap(page);
  assert.ok(s.inferred.evidence.some((f) => f.predicate === 'RoLi'), 'the inference ran with the learned rules');
  assert.equal(await page.isVisible('#message'), false, 'no error shown');
  assert.deepEqual(page.problems, []);
  await page.context().close();
});

test('frontier rules: the placeholders table, errors at line and column, re-run with hand-set weights', async () => {
  // The partly explored sample: its plan has frontiers.
  const page = await openPage(env, 'rules.html?sample=partial');
  const builtin = await page.inputValue('#frontier-kb');
  assert.match(builtin, /NewRoom\(place\)/);
  await until(page, 's.placeholders && s.placeholders.length > 0 && s.placeholderRows === s.placeholders.length');
  let s = await snap(page);
  assert.equal(s.frontierError, null);
  assert.equal(s.frontierUsed, builtin, 'the chain runs with the built-in frontier rules as shown');
  for (const p of s.placeholders) {
    assert.ok(p.p_new_room >= 0 && p.p_new_room <= 1);
    const sum = p.types.room + p.types.corridor + p.types.hall + p.types.other;
    assert.ok(Math.abs(sum - 1) < 0.01, `types sum to ${sum}`);
  }
  const first = s.placeholders.map((p) => p.p_new_room);

  // A missing query is refused with what to declare; the last good rules stay.
  await page.fill('#frontier-kb', 'Narrow(place)\n1 Narrow(p)\n');
  await settled(page);
  s = await snap(page);
  assert.ok(s.frontierError, 'the error is reported');
  assert.match(s.frontierErrorText, /must declare the query NewRoom\(place\)/);
  assert.equal(s.goodFrontier, builtin);
  // A syntax error at its line.
  const lines = builtin.split('\n');
  const i = lines.findIndex((l) => /Narrow\(p\)/.test(l) && !l.startsWith('//'));
  assert.ok(i >= 0, 'a rule on Narrow(p)');
  lines[i] = lines[i].replace('Narrow(p)', 'Narrow(p');
  await page.fill('#frontier-kb', lines.join('\n'));
  await settled(page);
  s = await snap(page);
  assert.equal(s.frontierError?.line, i + 1);

  // The hand-set weights, re-run: the chain runs with them and the placeholders change.
  await page.click('#frontier-handset');
  await settled(page);
  s = await snap(page);
  assert.equal(s.frontierError, null);
  assert.match(s.goodFrontier, /NewRoom/);
  assert.notEqual(s.goodFrontier, builtin);
  await page.click('#rerun');
  await until(page, 's.runs === 2 && s.placeholders && s.placeholders.length > 0');
  s = await snap(page);
  assert.equal(s.frontierUsed, s.goodFrontier);
  assert.notDeepEqual(s.placeholders.map((p) => p.p_new_room), first, 'the hand-set weights weigh the placeholders otherwise');

  const problems = page.problems;
  await page.context().close();
  assert.deepEqual(problems, [], 'the page logged errors');
});
