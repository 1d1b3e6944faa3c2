// The landing page opens on a plan (issue 33): the `mount` widget explains the office sample in
// the lead, on the page's thread in slices of a few milliseconds per frame, drawing the best
// world so far without controls, until the chain settles. A newcomer sees a result before they
// find the live mapper; if the widget cannot start, the lead's links still work.

import { mount } from '../pkg/mount.js';

const element = document.getElementById('lead-plan');
if (element) {
  try {
    const widget = await mount(element, { sample: 'office-small', seed: 1, autoplay: true, show: 'best', graph: false, controls: false, stopWhenSettled: true });
    window.__lead = widget;
  } catch (err) {
    element.textContent = `The sample could not be explained here: ${err instanceof Error ? err.message : String(err)}`;
  }
}
