// The mesh and export options remembered in this browser (localStorage):
// saved on every change, put back to the page's defaults by Reset. A new
// file starts from the defaults (the last patient's options are not the
// next one's), unless "Keep my settings for the next file" is checked (off
// by default; remembered): then the options are restored when the page
// opens and stay from file to file. They are also in the page's address (the hash,
// kept up to date: share.js), so a link gives them to someone else; opening
// a link with settings sets them (the link wins over this browser's, the
// controls it does not name get their defaults). Per-file choices (the
// input's units, cuts, opening names) are not settings.
import { byCurrentIds, controlSpec, decodeSettings, encodeSettings, linkNotice } from './share.js';

const KEY = 'vesselmesh.settings.v1';
const KEEP_KEY = 'vesselmesh.keep-settings.v1';

/** The remembered controls, by id (a control of one option: the option's JS
 * key in kebab-case, marked data-option in index.html; the others are the
 * page's compositions of options). Their order is the link's. */
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
  'prisms',
  'wall-on',
  'wall-thickness',
  'wall-layers',
  'param',
  'mesher2d',
  'fidelity-on',
  'decimate-on',
  'max-volume-change',
  'format',
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
  constructor({ onRestore = () => {}, storage = globalThis.localStorage, location = globalThis.location, history = globalThis.history } = {}) {
    this.onRestore = onRestore;
    this.storage = storage;
    this.location = location;
    this.history = history;
    this.controls = SETTING_IDS.map((id) => document.getElementById(id)).filter(Boolean);
    this.defaults = new Map(this.controls.map((el) => [el.id, read(el)]));
    this.specs = this.controls.map((el) => controlSpec(el, this.defaults.get(el.id)));
    this.keep = document.getElementById('keep-settings');
    this.files = 0; // files opened since the page opened
    if (this.keep) {
      this.keep.checked = this._get(KEEP_KEY) === '1';
      this.keep.addEventListener('change', () => this._set(KEEP_KEY, this.keep.checked ? '1' : '0'));
    }
  }

  _get(key) {
    try {
      return this.storage?.getItem(key) ?? null;
    } catch {
      return null; // storage refused
    }
  }

  _set(key, value) {
    try {
      this.storage?.setItem(key, value);
    } catch {
      // storage full or refused (private mode): not remembered
    }
  }

  /** Whether the options stay from one file to the next (and from one
   * visit to the next). */
  get keeping() {
    return Boolean(this.keep?.checked);
  }

  /**
   * A new file is opened: from the second file on, the options go back to
   * the defaults unless kept (the first file gets the options set before
   * it, or by a link). Returns whether they were put back (and differed).
   */
  newFile() {
    this.files++;
    if (this.files === 1 || this.keeping) return false;
    const changed = this.controls.some((el) => read(el) !== this.defaults.get(el.id));
    if (changed) this.reset();
    return changed;
  }

  /**
   * Sets the controls to the remembered values (if any), then to the
   * link's (the address' hash), which win. Returns what the link did:
   * {given: whether the address had settings, changed: the ids whose value
   * differs from this browser's (none on a reload of the page's own
   * address), problems: its settings that were ignored, as 'name=value:
   * must be ...'}.
   */
  restore() {
    let saved = null;
    try {
      saved = this.keeping ? JSON.parse(this._get(KEY) ?? 'null') : null;
    } catch {
      saved = null; // unreadable: the defaults
    }
    if (saved && typeof saved === 'object') {
      // Remembered before a control was renamed: under its old id.
      const values = byCurrentIds(saved);
      for (const el of this.controls) if (el.id in values) write(el, values[el.id]);
    }
    const link = decodeSettings(this.location?.hash ?? '', this.specs);
    const changed = [];
    if (link.given) {
      for (const el of this.controls) {
        const before = read(el);
        write(el, el.id in link.values ? link.values[el.id] : this.defaults.get(el.id));
        if (read(el) !== before) changed.push(el.id);
      }
    }
    this.onRestore();
    // The link's settings are now this browser's; the address shows the
    // settings in use (without a link's ignored ones).
    if (link.given) this.save();
    else this._address();
    return { given: link.given, changed, problems: link.problems };
  }

  /** The controls' values, by id. */
  values() {
    return new Map(this.controls.map((el) => [el.id, read(el)]));
  }

  /** The hash of a link with the current settings ('' for the defaults). */
  hash() {
    return encodeSettings(SETTING_IDS, this.values(), this.defaults);
  }

  /** The page's address with the current settings: a link to share. */
  link() {
    const loc = this.location;
    return `${loc.origin === 'null' ? loc.href.replace(/#.*$/, '') : `${loc.origin}${loc.pathname}${loc.search}`}${this.hash()}`;
  }

  /** Remembers the controls' values, and puts them in the address. */
  save() {
    this._set(KEY, JSON.stringify(Object.fromEntries(this.values())));
    this._address();
  }

  /** The address' hash follows the settings (no new history entry). */
  _address() {
    const loc = this.location;
    if (!loc || !this.history?.replaceState) return;
    const hash = this.hash();
    if (hash === loc.hash || (!hash && !loc.href.includes('#'))) return;
    try {
      this.history.replaceState(this.history.state, '', `${loc.href.replace(/#.*$/, '')}${hash}`);
    } catch {
      // an address that cannot be replaced (some file:// pages): not shown there
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
    this._address();
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

/**
 * The settings' link controls: "Copy link" puts settings.link() on the
 * clipboard (and shows it, selected, when the clipboard is refused); what
 * an opened link set and ignored (`link`, from restore()) is said in the
 * action bar until dismissed.
 * @param {Settings} settings
 * @param {{changed: string[], problems: string[]}} link
 * @param {(text: string) => void} announce
 */
export function listenShareLink(settings, link, announce) {
  const $ = (id) => document.getElementById(id);
  const notice = $('link-notice');
  const name = (id) => settings.specs.find((s) => s.id === id)?.name ?? id;
  const text = linkNotice(link.changed.map(name), link.problems);
  if (text) {
    $('link-notice-text').textContent = text;
    notice.hidden = false;
  }
  $('link-notice-dismiss').addEventListener('click', () => {
    notice.hidden = true;
  });
  $('copy-link').addEventListener('click', async () => {
    const link = settings.link();
    const field = $('share-link');
    field.value = link;
    $('share-link-field').hidden = false;
    let copied = false;
    try {
      await navigator.clipboard.writeText(link);
      copied = true;
    } catch {
      copied = false; // refused (no permission, not a secure page): the field is there to copy from
    }
    field.select();
    $('share-link-status').textContent = copied ? 'Copied.' : 'Select and copy it (the clipboard was refused).';
    announce(copied ? 'Link to these options copied' : 'The link is shown selected: copy it');
  });
}
