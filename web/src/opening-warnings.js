// The openings' warnings (opening-check.js) in the page: listed above the
// openings, each with its remedy's button; and at a Mesh or Export press,
// said in the action bar with their places marked, the fix as the first
// (primary) button when the page has one (the cuts: made, then the press
// goes on), and "Mesh anyway" (once per analysis) before the model is
// meshed with openings that look wrong.
import { openingWarnings } from './opening-check.js';
import { remedyLabel } from './remedies.js';

const $ = (id) => document.getElementById(id);

export class OpeningWarnings {
  /**
   * @param {object} hooks
   * @param {import('./action-bar.js').ActionBar} hooks.bar
   * @param {import('./problems.js').Problems} hooks.problems marks places
   * @param {() => {unit: string, scale: number}} hooks.model
   * @param {(remedy: object, then?: () => Promise<void>) => Promise<void>} hooks.apply
   *   applies a remedy; `then`: the press to go on with once it is applied
   */
  constructor({ bar, problems, model, apply }) {
    Object.assign(this, { bar, problems, model, apply });
    this.warnings = [];
    this.accepted = false;
  }

  /** Checks the openings of a new analysis (`file`: its first proposals). */
  show(analysis, file) {
    this.warnings = openingWarnings(analysis, file);
    this.accepted = false;
    const items = this.warnings.map((w) => {
      const li = document.createElement('li');
      li.setAttribute('data-testid', 'opening-warning');
      li.dataset.warning = w.id;
      li.append(w.text);
      if (w.remedy) {
        const button = document.createElement('button');
        button.type = 'button';
        button.textContent = remedyLabel(w.remedy, this.model());
        button.setAttribute('data-testid', `warning-${w.remedy.action}`);
        button.addEventListener('click', () => this.apply(w.remedy));
        li.append(' ', button);
      }
      return li;
    });
    $('openings-check').replaceChildren(...items);
    $('openings-check').hidden = items.length === 0;
    this.problems.showPlaces(this.warnings.flatMap((w) => w.places), 'to check before meshing');
  }

  /** Whether meshing may go on: no warning, or the user said so once; else
   * the warnings are said in the bar with the way forward (the first
   * warning's fix that the page can apply, then `again`: the press that was
   * stopped; or "Mesh anyway", which calls `again` at once), and false. */
  allowMesh(again) {
    const blocking = this.warnings.filter((w) => w.blocking);
    if (!blocking.length || this.accepted) return true;
    const fix = blocking.find((w) => w.remedy)?.remedy;
    const actions = [];
    if (fix) {
      actions.push({
        label: remedyLabel(fix, this.model()),
        testId: `remedy-${fix.action}`,
        run: () => this.apply(fix, again),
      });
    }
    actions.push({
      label: 'Mesh anyway',
      testId: 'mesh-anyway',
      run: () => {
        this.accepted = true;
        this.problems.clear();
        again();
      },
    });
    this.problems.stage = 'mesh';
    this.problems.showPlaces(blocking.flatMap((w) => w.places), 'an opening to check');
    this.bar.error(
      `The openings look wrong: ${blocking.map((w) => w.text).join(' ')}`,
      'Fix the openings (the button above, or Prepare), or mesh as they are.',
      actions,
      { focus: true },
    );
    return false;
  }
}
