// The mesh and export options remembered in this browser (localStorage):
// saved on every change, restored when the page opens, and put back to the
// page's defaults by Reset. Per-file choices (the input's units, cuts,
// opening names) are not settings.

const KEY = 'vesselmesh.settings.v1';

/** The remembered controls, by id. */
export const SETTING_IDS = [
  'solver',
  'size-mode',
  'size-value',
  'surface-only',
  'core-size',
  'layers',
  'layer-mode',
  'layer-thickness',
  'first-layer',
  'first-layer-yplus',
  'inlet-velocity',
  'density',
  'viscosity',
  'growth',
  'tag-layer',
  'keep-prisms',
  'wall-on',
  'wall-thickness',
  'wall-layers',
  'param',
  'mesher2d',
  'fidelity-on',
  'max-volume-change',
  'export-format',
  'output-units',
];

const read = (el) => (el.type === 'checkbox' ? el.checked : el.value);

function write(el, value) {
  if (el.type === 'checkbox') el.checked = Boolean(value);
  else if (el.tagName === 'SELECT' && ![...el.options].some((o) => o.value === value)) return;
  else el.value = String(value);
  el.removeAttribute('aria-invalid');
}

export class Settings {
  /**
   * @param {object} hooks onRestore: called after the controls were set
   *   (restore, reset), to update what depends on them
   */
  constructor({ onRestore = () => {}, storage = globalThis.localStorage } = {}) {
    this.onRestore = onRestore;
    this.storage = storage;
    this.controls = SETTING_IDS.map((id) => document.getElementById(id)).filter(Boolean);
    this.defaults = new Map(this.controls.map((el) => [el.id, read(el)]));
  }

  /** Sets the controls to the remembered values (if any). */
  restore() {
    let saved = null;
    try {
      saved = JSON.parse(this.storage?.getItem(KEY) ?? 'null');
    } catch {
      saved = null; // unreadable: the defaults
    }
    if (!saved || typeof saved !== 'object') return false;
    for (const el of this.controls) if (el.id in saved) write(el, saved[el.id]);
    this.onRestore();
    return true;
  }

  /** Remembers the controls' values. */
  save() {
    try {
      this.storage?.setItem(KEY, JSON.stringify(Object.fromEntries(this.controls.map((el) => [el.id, read(el)]))));
    } catch {
      // storage full or refused (private mode): not remembered
    }
  }

  /** Forgets the remembered values and puts the defaults back. */
  reset() {
    try {
      this.storage?.removeItem(KEY);
    } catch {
      // nothing remembered
    }
    for (const el of this.controls) write(el, this.defaults.get(el.id));
    this.onRestore();
  }

  /** Saves whenever a remembered control changes (after the page's own
   * handlers, which may set other controls). */
  listen() {
    const ids = new Set(this.controls.map((el) => el.id));
    for (const type of ['change', 'input']) {
      document.addEventListener(type, (e) => ids.has(e.target.id) && this.save());
    }
  }
}
