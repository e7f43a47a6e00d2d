// "Reset everything": the mesh and export options (settings.js), the view's
// controls, the preparation's fields, and the loaded file analyzed again
// as first opened (units guessed, caps and components as read, smoothing
// and repair automatic, the proposed cuts, the default opening names and
// inlet, no flow extension, no refinement, no mesh), the view fitted. The
// preparation before it stays in the undo history.

const $ = (id) => document.getElementById(id);

/** The view's controls, put back to the page's defaults. */
export const VIEW_CONTROLS = [
  'wireframe',
  'clip-axis',
  'clip-position',
  'clip-flip',
  'volume-color',
  'show-boundary',
  'show-edges',
  'tet-histogram-all',
];

/** The preparation's fields that the analyze options do not set. */
export const PREP_FIELDS = ['smooth-passes', 'hole-fraction', 'flow-all'];

/** The default (in the page's HTML) of a control's value. */
export function defaultOf(el) {
  if (el.type === 'checkbox' || el.type === 'radio') return el.defaultChecked;
  if (el.tagName === 'SELECT') {
    const chosen = [...el.options].find((o) => o.defaultSelected) ?? el.options[0];
    return chosen?.value ?? '';
  }
  return el.defaultValue;
}

/** Sets the controls `ids` to their defaults; with `events`, those that
 * change get a change event (and input, for sliders), so the page follows. */
export function resetControls(ids, { events = true } = {}) {
  for (const id of ids) {
    const el = $(id);
    if (!el) continue;
    const value = defaultOf(el);
    const checkable = el.type === 'checkbox' || el.type === 'radio';
    if ((checkable ? el.checked : el.value) === value) continue;
    if (checkable) el.checked = value;
    else el.value = value;
    el.removeAttribute('aria-invalid');
    if (!events) continue;
    if (el.type === 'range' || el.type === 'number') el.dispatchEvent(new Event('input', { bubbles: true }));
    el.dispatchEvent(new Event('change', { bubbles: true }));
  }
}

/**
 * Resets everything.
 * @param {object} hooks
 * @param {import('./settings.js').Settings} hooks.settings
 * @param {() => Promise<string|null>} hooks.reload analyzes the loaded file
 *   again as when first opened (none loaded: resolves null at once)
 * @param {() => void} hooks.fit fits the view
 */
export async function resetAll({ settings, reload, fit }) {
  settings.reset();
  // Quietly: the file is analyzed again once, below, with them.
  resetControls(PREP_FIELDS, { events: false });
  resetControls(VIEW_CONTROLS);
  const error = await reload();
  fit();
  return error;
}
