// Undo and redo of the Prepare step: the units, the caps and components
// choices, smoothing, repairs, the cuts (listed and made), the openings'
// inlet, names and flow extensions. A state is recorded after every change
// of them settles (an analysis done, a cut added, moved or removed, a name
// typed); Undo and Redo (the buttons of the action bar, Ctrl+Z and
// Ctrl+Shift+Z or Ctrl+Y outside text fields) put a recorded state back:
// analyzed again when its analyze options differ (the view, the openings
// and the proposed cuts follow), its cuts and openings set.
import { UndoHistory } from './history.js';

const $ = (id) => document.getElementById(id);
// A change is recorded once nothing more changed for this long (a slider
// dragged or a name typed is one change).
const SETTLE_MS = 400;

/** Whether the key press belongs to a text field's own undo. */
function inTextField(target) {
  if (!(target instanceof HTMLElement)) return false;
  if (target.isContentEditable || target.tagName === 'TEXTAREA') return true;
  return target.tagName === 'INPUT' && !['checkbox', 'radio', 'range', 'button', 'submit', 'file'].includes(target.type);
}

export class PrepHistory {
  /**
   * @param {object} hooks
   * @param {() => object|null} hooks.current the loaded file ({prep, ...}) or null
   * @param {import('./prepare.js').Prepare} hooks.prepare
   * @param {import('./openings.js').OpeningsTable} hooks.openings
   * @param {(prep: object, names: string[]) => Promise<string|null>} hooks.reanalyze
   *   analyzes the file again with the analyze options `prep`, keeping the
   *   typed opening `names`; the error, or null
   * @param {() => boolean} hooks.isBusy a job runs (nothing is undone then)
   * @param {(text: string) => void} hooks.announce
   */
  constructor({ current, prepare, openings, reanalyze, isBusy, announce }) {
    Object.assign(this, { current, prepare, openings, reanalyze, isBusy, announce });
    this.history = new UndoHistory();
    this.timer = null;
    this.restoring = false;
    this.busy = false;
    $('undo').addEventListener('click', () => this.undo());
    $('redo').addEventListener('click', () => this.redo());
    document.addEventListener('keydown', (e) => this._key(e));
    // The openings' choices: the inlet, names, flow extensions.
    for (const type of ['change', 'input']) $('openings').addEventListener(type, () => this.schedule());
    $('flow-all').addEventListener('input', () => this.schedule());
    this._render();
  }

  /** The preparation as shown: the analyze options of the shown analysis,
   * the listed cuts and the openings' choices. */
  snapshot() {
    const file = this.current();
    return {
      prep: structuredClone(file.prep),
      ...this.prepare.cutState(),
      openings: this.openings.state(),
    };
  }

  /** A new file: its history starts from its first state. */
  start() {
    clearTimeout(this.timer);
    this.history.start(this.snapshot());
    this._render();
  }

  /** Records the shown state now (after an analysis). */
  record() {
    clearTimeout(this.timer);
    if (this.restoring || !this.current()) return;
    if (this.history.push(this.snapshot())) this._render();
  }

  /** Records the shown state once the changes settle. */
  schedule() {
    if (this.restoring || !this.current()) return;
    clearTimeout(this.timer);
    this.timer = setTimeout(() => {
      if (this.isBusy() || this.restoring || this.prepare.moving) this.schedule();
      else this.record();
    }, SETTLE_MS);
  }

  /** Off while a worker job runs (on: the job started, off: it ended). */
  setBusy(on) {
    this.busy = on;
    this._render();
  }

  async undo() {
    await this._go(-1);
  }

  async redo() {
    await this._go(1);
  }

  /** Puts back the state one step back (-1) or forward (1). */
  async _go(step) {
    if (!this.current() || this.isBusy() || this.restoring) return;
    // A change not recorded yet is recorded first: undo takes it back.
    this.record();
    const label = step < 0 ? this.history.undoLabel() : this.history.redoLabel();
    const state = step < 0 ? this.history.undo() : this.history.redo();
    if (!state) return;
    this.restoring = true;
    this._render();
    let ok = false;
    try {
      ok = await this._restore(state);
    } finally {
      this.restoring = false;
    }
    clearTimeout(this.timer);
    if (!ok) {
      // Not put back: the history stays where the page is.
      if (step < 0) this.history.redo();
      else this.history.undo();
    } else {
      this.announce(`${step < 0 ? 'Undone' : 'Redone'}: ${label}`);
    }
    this._render();
  }

  async _restore(state) {
    const file = this.current();
    if (JSON.stringify(state.prep) !== JSON.stringify(file.prep)) {
      const error = await this.reanalyze(structuredClone(state.prep), state.openings.names);
      if (error) return false;
    }
    this.prepare.setCutState(state);
    this.openings.setState(state.openings);
    return true;
  }

  _key(e) {
    if (!(e.ctrlKey || e.metaKey) || e.altKey || e.defaultPrevented || inTextField(e.target)) return;
    const key = e.key.toLowerCase();
    const redo = (key === 'z' && e.shiftKey) || (key === 'y' && !e.shiftKey);
    const undo = key === 'z' && !e.shiftKey;
    if (!undo && !redo) return;
    if (!this.current()) return;
    e.preventDefault();
    if (undo) this.undo();
    else this.redo();
  }

  _render() {
    $('history-actions').hidden = !this.current();
    const off = !this.current() || this.busy || this.restoring;
    const undo = $('undo');
    const redo = $('redo');
    undo.disabled = off || !this.history.canUndo;
    redo.disabled = off || !this.history.canRedo;
    const u = this.history.undoLabel();
    const r = this.history.redoLabel();
    undo.title = u ? `Undo the change of the ${u} (Ctrl+Z)` : 'Undo a preparation change (Ctrl+Z)';
    redo.title = r ? `Redo the change of the ${r} (Ctrl+Shift+Z)` : 'Redo a preparation change (Ctrl+Shift+Z)';
    undo.setAttribute('aria-label', u ? `Undo: ${u}` : 'Undo');
    redo.setAttribute('aria-label', r ? `Redo: ${r}` : 'Redo');
    undo.dataset.change = u;
    redo.dataset.change = r;
    document.body.dataset.history = `${this.history.index + 1}/${this.history.states.length}`;
  }
}
