// Saving bytes the page made (a map, a world, a report) as a file the browser downloads.

/**
 * Offers `data` for download as `name`. The link is attached while it is clicked (Firefox
 * ignores clicks on detached links) and its object URL is revoked once the download started.
 * @param {string} name file name
 * @param {BlobPart} data the file's contents
 * @param {string} type its MIME type
 */
export function download(name, data, type) {
  const url = URL.createObjectURL(new Blob([data], { type }));
  const a = document.createElement('a');
  a.href = url;
  a.download = name;
  a.hidden = true;
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10_000);
}
