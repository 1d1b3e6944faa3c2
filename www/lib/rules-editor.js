// The knowledge-base editor shared by the rules, prior-shaping and table-top pages: a plain
// textarea with line numbers, the offending line marked in the gutter, the offending token
// underlined at the parser's line and column, and the message below. The pages differ only in
// how they check the text (`checkRules`, `tabletopCheckRules`, or more); the editor shows what
// the check says.
//
// The underline is drawn by a <pre> behind a transparent textarea holding the same text in the
// same font, so the browser's own editing (undo, selection, keyboard, screen readers) is kept.

/**
 * A parse error as the wasm functions report it: 1-based line and column (0 when unknown).
 * @typedef {{ line: number, column: number, message: string }} RuleError
 */

/**
 * The span to underline for an error at 1-based `line`, `column` of `text`: the word starting
 * there (letters, digits, `_`, `.`), or the connective (`=>`, `<=>`), else the one character
 * there, else (past the end of the line) an empty span at its end. Returns `{ start, end }` offsets into `text`, or null when the
 * position is not in the text.
 * @param {string} text
 * @param {number} line
 * @param {number} column
 * @returns {{ start: number, end: number } | null}
 */
export function errorSpan(text, line, column) {
  if (!Number.isInteger(line) || !Number.isInteger(column) || line < 1 || column < 1) return null;
  let start = 0;
  for (let l = 1; l < line; l++) {
    const nl = text.indexOf('\n', start);
    if (nl < 0) return null;
    start = nl + 1;
  }
  let lineEnd = text.indexOf('\n', start);
  if (lineEnd < 0) lineEnd = text.length;
  const at = Math.min(start + column - 1, lineEnd);
  if (at >= lineEnd) return { start: lineEnd, end: lineEnd };
  const kind = [/[A-Za-z0-9_.]/, /[=<>]/].find((re) => re.test(text[at]));
  let end = at + 1;
  if (kind) while (end < lineEnd && kind.test(text[end])) end++;
  return { start: at, end };
}

/** The message line for an error: `line L, column C: message`, or the message alone. */
export function errorText(err) {
  if (!err) return '';
  return err.line > 0 ? `line ${err.line}, column ${err.column}: ${err.message}` : err.message;
}

/**
 * Wraps `textarea` in the editor's boxes: the line-number gutter beside it and the marks (the
 * same text, with the underline) behind it. Returns the gutter and the marks.
 */
function wrapTextarea(textarea, status, gutterId) {
  const doc = textarea.ownerDocument;
  const box = doc.createElement('div');
  box.className = 'rules-editor';
  const gutter = doc.createElement('pre');
  gutter.className = 'rules-gutter';
  gutter.setAttribute('aria-hidden', 'true');
  if (gutterId) gutter.id = gutterId;
  const text = doc.createElement('div');
  text.className = 'rules-text';
  const marks = doc.createElement('pre');
  marks.className = 'rules-marks';
  marks.setAttribute('aria-hidden', 'true');
  textarea.replaceWith(box);
  text.append(marks, textarea);
  box.append(gutter, text);
  textarea.classList.add('rules-input');
  textarea.spellcheck = false;
  if (status.id) textarea.setAttribute('aria-describedby', status.id);
  return { gutter, marks };
}

/** Numbers the gutter's `lines` lines, the 1-based `badLine` (0: none) marked bad. */
function drawGutter(gutter, lines, badLine) {
  const doc = gutter.ownerDocument;
  gutter.replaceChildren(
    ...Array.from({ length: lines }, (_, i) => {
      const s = doc.createElement('span');
      s.textContent = `${i + 1}\n`;
      if (i + 1 === badLine) s.className = 'bad';
      return s;
    }),
  );
}

/** Puts `value` into the marks behind the textarea, the span of `error` (if any) underlined. */
function drawMarks(marks, value, error) {
  const span = error ? errorSpan(value, error.line, error.column) : null;
  if (span) {
    const mark = marks.ownerDocument.createElement('span');
    mark.className = 'err';
    // An error past the end of a line still gets something to underline.
    mark.textContent = span.end > span.start ? value.slice(span.start, span.end) : '\u00a0';
    mark.title = error.message;
    marks.replaceChildren(value.slice(0, span.start), mark, value.slice(span.end), '\n');
  } else {
    marks.replaceChildren(value, '\n');
  }
}

/**
 * Turns `textarea` into the knowledge-base editor and checks its text on every edit.
 *
 * @param {HTMLTextAreaElement} textarea  keeps its id, label and attributes
 * @param {object} options
 * @param {(text: string) => RuleError | null} options.check  null when the text is good
 * @param {HTMLElement} options.status  where the message goes (a `role="status"` element)
 * @param {string} [options.okText]  shown in `status` when the text is good
 * @param {string} [options.gutterId]  id for the line-number gutter
 * @param {(text: string, err: RuleError | null) => void} [options.onCheck]  after each check
 * @param {number} [options.delayMs]  wait this long after typing before checking (0: at once)
 * @returns {{ check(): RuleError | null, readonly error: RuleError | null, readonly badLine: number }}
 */
export function rulesEditor(textarea, { check, status, okText = '', gutterId, onCheck, delayMs = 0 }) {
  const { gutter, marks } = wrapTextarea(textarea, status, gutterId);

  let error = null;
  let badLine = 0;

  const syncScroll = () => {
    gutter.scrollTop = textarea.scrollTop;
    marks.scrollTop = textarea.scrollTop;
    marks.scrollLeft = textarea.scrollLeft;
  };

  const draw = (value) => {
    drawGutter(gutter, value.split('\n').length, badLine);
    drawMarks(marks, value, error);
    syncScroll();
  };

  const run = () => {
    const value = textarea.value;
    error = check(value) ?? null;
    badLine = error && error.line > 0 ? error.line : 0;
    status.textContent = error ? errorText(error) : okText;
    status.dataset.ok = error ? 'false' : 'true';
    textarea.setAttribute('aria-invalid', error ? 'true' : 'false');
    draw(value);
    onCheck?.(value, error);
    return error;
  };

  let timer = 0;
  textarea.addEventListener('input', () => {
    // Keep the underline in step with the text while the check waits.
    if (delayMs > 0) {
      draw(textarea.value);
      clearTimeout(timer);
      timer = setTimeout(run, delayMs);
    } else {
      run();
    }
  });
  textarea.addEventListener('scroll', syncScroll);
  run();
  return {
    check: run,
    get error() {
      return error;
    },
    get badLine() {
      return badLine;
    },
  };
}
