// The map's legend as page text beside the picture: one swatch per colour the renderer can put
// on the map (the room types' tints, walls, doors, objects, unexplained space, the placeholders'
// rim), read from the library (`legendJson`) so that the colours are the picture's. The picture
// is drawn without its own legend, which at the page's size would be too small to read (issue 33).

/**
 * Fills element `el` with the rows of `rowsJson` (`legendJson()`'s text): a swatch and a name
 * each. `names` renames rows for the reader (e.g. `{ wall: 'walls' }`).
 */
export function fillMapLegend(el, rowsJson, names = {}) {
  const rows = JSON.parse(rowsJson);
  el.replaceChildren(
    ...rows.map(({ name, rgba }) => {
      const row = document.createElement('span');
      const swatch = document.createElement('i');
      swatch.style.background = `rgb(${rgba[0]} ${rgba[1]} ${rgba[2]} / ${(rgba[3] / 255).toFixed(3)})`;
      row.dataset.name = name;
      row.append(swatch, names[name] ?? name);
      return row;
    }),
  );
}
