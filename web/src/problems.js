// A refusal as the page shows it, where the user is looking (the action
// bar): what failed and the message in the page's words, the remedy as a
// button that applies it, the places the message names marked in the view
// (numbered marks that zoom there), and, when the message itself stands
// next to a control in the panel (a cut, a field), a button that brings it
// into sight. Cleared when the user changes what caused it (clear()).
import { placesIn, remedyLabel, remedyOf } from './remedies.js';
import { inPageWords } from './words.js';

export class Problems {
  /**
   * @param {object} hooks
   * @param {import('./action-bar.js').ActionBar} hooks.bar
   * @param {import('./view-marks.js').ViewMarks} hooks.marks
   * @param {() => {unit: string, scale: number}} hooks.model the loaded model
   * @param {() => object} hooks.context what remedies are read with
   *   (remedies.js fromMessage: the size asked, the proposed cuts)
   * @param {(remedy: object, stage: string) => Promise<void>} hooks.apply
   *   applies a remedy of a failure at `stage` ('mesh', 'prepare', 'read')
   */
  constructor({ bar, marks, model, context, apply }) {
    Object.assign(this, { bar, marks, model, context, apply });
    this.stage = null; // the stage of the shown problem, or null
  }

  /** The message of `error` (a core message) in the page's words. */
  words(error) {
    return inPageWords(error, this.model());
  }

  /**
   * Shows a failure: {error, remedy?, option?, cancelled?} of `stage`
   * ('mesh', 'prepare', 'read'); `prefix` before its message (what failed:
   * 'Mesh failed: x.stl: '), `next` what to do (the bar's hint), `panel` the
   * element of the panel that says it too (null: the bar alone).
   */
  show(failure, { stage, prefix = '', next, panel = null }) {
    const message = failure.cancelled ? 'Cancelled.' : `${prefix}${this.words(failure.error)}`;
    const remedy = failure.cancelled ? null : remedyOf(failure, this.context());
    // Every place the message names (a crossing, a failed patch) and the remedy's.
    const key = (p) => p.map((x) => Number(x).toPrecision(5)).join(',');
    const places = [...(remedy?.places ?? []), ...placesIn(failure.error ?? '')].filter(
      (p, i, all) => all.findIndex((q) => key(q) === key(p)) === i,
    );
    const actions = [];
    if (remedy) {
      const label = remedyLabel(remedy, this.model());
      const run = () => this.apply(remedy, stage);
      if (label) actions.push({ label, testId: `remedy-${remedy.action}`, run });
    }
    this.showPlaces(places, 'named in the message');
    this.text(message, { stage, next, panel, actions });
  }

  /** Shows `message` (in the page's words already) as a problem of
   * `stage`, with `actions` ({label, run, testId}) and, when `panel` (an
   * element of the panel) says it in full, a button that brings it into
   * sight. */
  text(message, { stage, next, panel = null, actions = [] }) {
    const all = [...actions];
    if (panel) {
      all.push({
        label: 'Show the message',
        testId: 'show-message',
        run: () => {
          panel.scrollIntoView({ block: 'center', behavior: 'instant' });
          panel.focus({ preventScroll: true });
        },
      });
    }
    this.stage = stage;
    // A remedy's button takes the focus: the way forward is one key away.
    this.bar.error(message, next, all, { focus: actions.length > 0 });
  }

  /** Marks `places` (points, or {point, radius, what}) in the view, as
   * warnings or (tone 'info') as facts; with zoom, the view turns to the
   * first. */
  showPlaces(places, what = '', { zoom = false, tone = 'warn' } = {}) {
    const radius = this.model().scale / 40;
    const items = places.map((p) => (Array.isArray(p) ? { point: p, radius, what } : p));
    this.marks.setPlaces(items, { tone });
    if (zoom && items.length) this.marks.viewer.focusOn(items[0].point, items[0].radius);
  }

  /** Takes the shown problem and its marks away (a job starts, or the
   * user changed what caused it); with `unless`, not a problem of that
   * stage (a file that cannot be read stays said while options change).
   * Marks put without a problem (the verdict's, the warnings') stay until
   * replaced. */
  clear(unless = null) {
    if (this.stage === null || (unless && this.stage === unless)) return;
    this.bar.clearError();
    this.stage = null;
    this.marks.setPlaces([]);
  }
}
