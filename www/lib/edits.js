// A person's corrections of the floor plan (docs/formats.md, "Correcting a floor plan"), as the page
// keeps and shows them: the list `Mapper.setEdits` takes, in map cells. The wasm checks the
// list and holds it as hard evidence; this module only makes edits and words them.

/** The room types an edit may set. */
export const EDIT_TYPES = ['room', 'corridor', 'hall', 'other'];

const at = ([x, y]) => `(${x}, ${y})`;

/** One edit in a few words, e.g. "merge (3, 4) with (9, 4)". */
export function describeEdit(e) {
  switch (e.op) {
    case 'merge':
      return `merge ${at(e.at[0])} with ${at(e.at[1])}`;
    case 'split':
      return `split along ${at(e.line[0])}–${at(e.line[1])}`;
    case 'type':
      return `${at(e.at)} is a ${e.type}`;
    case 'name':
      return `${at(e.at)} is named “${e.name}”`;
    default:
      return JSON.stringify(e);
  }
}

/**
 * The edits of an imported file's text, or an Error that says what is wrong (the wasm checks
 * the points and fields when the list is sent).
 */
export function parseEdits(text) {
  let list;
  try {
    list = JSON.parse(text);
  } catch (err) {
    return new Error(`the edits file is not JSON: ${err.message}`);
  }
  if (!Array.isArray(list)) return new Error('the edits file must hold a JSON list of edits, such as [{"op": "type", "at": [10, 12], "type": "hall"}]');
  return list;
}
