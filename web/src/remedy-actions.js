// Applying a remedy (remedies.js) with the page's own controls, as the
// user would: a cut at each place ("Cut here", "Trim the damaged end"),
// the repairs or the largest piece or N smoothing passes (the surface is
// analyzed again), a coarser size or no boundary layer (meshed again), the
// units question brought into sight. The controls changed get their input
// and change events, so everything that follows them (the remembered
// options, the labels, the size view) does.

const $ = (id) => document.getElementById(id);

/** Sets a control's value as if typed or chosen. */
function setControl(id, value) {
  const el = $(id);
  if (el.type === 'checkbox') el.checked = Boolean(value);
  else el.value = String(value);
  el.removeAttribute('aria-invalid');
  el.dispatchEvent(new Event('input', { bubbles: true }));
  el.dispatchEvent(new Event('change', { bubbles: true }));
}

/**
 * Applies `remedy` of a failure at `stage` ('mesh': the mesh is made again
 * after a change of the options or of the surface that fixes it, the cuts
 * included).
 * @param {{action: string, places: number[][], value: number, mode?: string}} remedy
 * @param {string} stage
 * @param {object} hooks
 * @param {import('./prepare.js').Prepare} hooks.prepare
 * @param {(prep?: object) => Promise<string|null>} hooks.reanalyze analyzes
 *   again with the panel's analyze options; the error or null
 * @param {() => Promise<void>} hooks.mesh presses Mesh (or the press that
 *   was stopped: Export)
 */
export async function applyRemedy(remedy, stage, { prepare, reanalyze, mesh }) {
  const { action, value } = remedy;
  switch (action) {
    case 'trim_end':
    case 'cut_here': {
      const error = await prepare.cutAtPlaces(remedy.places, { trim: action === 'trim_end' });
      if (!error && stage === 'mesh') await mesh();
      return;
    }
    case 'units':
      $('units-prompt').hidden = false;
      $('units-prompt').scrollIntoView({ block: 'center', behavior: 'instant' });
      $('units-prompt').querySelector('button')?.focus({ preventScroll: true });
      return;
    case 'repair':
    case 'largest_component':
    case 'smooth': {
      // Quietly (no change events): the surface is analyzed once, here.
      if (action === 'repair') $('repair').value = 'auto';
      if (action === 'largest_component') $('largest-component-only').checked = true;
      if (action === 'smooth') {
        $('smooth').value = 'passes';
        $('smooth-passes').value = String(value || 10);
        $('smooth-passes-field').hidden = false;
      }
      const error = await reanalyze();
      if (!error && stage === 'mesh') await mesh();
      return;
    }
    case 'coarser':
      if (remedy.mode === 'coreSize') setControl('core-size', value);
      else {
        const mode = remedy.mode === 'perCircumference' ? 'perCircumference' : 'size';
        if ($('size-mode').value !== mode) setControl('size-mode', mode);
        setControl('size-value', value);
      }
      await mesh();
      return;
    case 'no_layers':
      setControl('layers', 0);
      await mesh();
      return;
    default:
  }
}
