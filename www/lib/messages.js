// The page's alert and status line, the same on every page.
//
// `ui.message` is the role="alert" box, `ui.messageText` its text, `ui.messageClose` its
// Dismiss button, `ui.status` the status line: the box is the same on every page (the pages'
// shell, which scripts/check-shell.mjs keeps the same), and its button is wired here.

/** Error and status helpers bound to a page's `ui` elements. */
export function messages(ui) {
  /** Shows an error in the alert (first unhidden, then filled, so screen readers announce it). */
  function showError(err) {
    const text = err instanceof Error ? err.message : String(err);
    ui.message.hidden = false;
    ui.messageText.textContent = text;
    if (ui.status) ui.status.textContent = '';
  }

  function clearError() {
    ui.message.hidden = true;
    ui.messageText.textContent = '';
  }

  function say(text) {
    ui.status.textContent = text;
  }

  /** Runs `fn`; a thrown error goes to the alert and the page carries on as it was. */
  async function attempt(fn) {
    try {
      await fn();
      return true;
    } catch (err) {
      console.warn(err);
      showError(err);
      return false;
    }
  }

  /**
   * Loads the WebAssembly module with `init` (the package's default export); if it fails,
   * marks the page as broken and says how to get the module. Returns whether it loaded.
   */
  async function loadWasm(init) {
    try {
      await init();
      return true;
    } catch (err) {
      document.documentElement.dataset.state = 'error';
      showError(
        `The WebAssembly module did not load (${err.message}). Build it with \`make demo\`, ` +
          'and open the page through a web server rather than from the file system.',
      );
      return false;
    }
  }

  ui.messageClose?.addEventListener('click', clearError);

  return { showError, clearError, say, attempt, loadWasm };
}
