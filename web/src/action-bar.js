// The action bar at the bottom of the panel (of the screen on phones): the
// workflow's steps with the current one marked, what to do next, the
// running job's progress (monotonic, stage, elapsed, time left) with
// Cancel, the last error with the buttons that act on it (a remedy, the
// way to the message in the panel), a notice of what a change did with its
// Undo, and the primary actions (Mesh, Export). A polite live region
// announces stage changes and errors.
import { JobProgress } from './progress.js';

const $ = (id) => document.getElementById(id);

export const STEPS = ['load', 'prepare', 'mesh', 'inspect', 'export'];

/** What to do next at each step. */
const NEXT = {
  load: 'Open a surface file (STL, VTP, VTK, OBJ or PLY, or gzipped) or load the sample.',
  prepare: 'Check the units, cuts and openings above, choose the size, then press Mesh.',
  mesh: 'Meshing: wait for it, or Cancel.',
  inspect: 'Read the verdict in the panel, inspect the mesh in the view; choose a format and press Export.',
  export: 'Exported. Change the options and press Mesh again, or open another file.',
};

export class ActionBar {
  constructor() {
    this.job = null;
    this.timer = null;
    this.current = 'load';
  }

  /** Marks `step` (one of STEPS) as the current one; `next` replaces its
   * hint. */
  step(step, next = NEXT[step]) {
    this.current = step;
    for (const li of $('steps').children) {
      if (li.dataset.step === step) li.setAttribute('aria-current', 'step');
      else li.removeAttribute('aria-current');
      li.classList.toggle('done', STEPS.indexOf(li.dataset.step) < STEPS.indexOf(step));
    }
    document.body.dataset.step = step;
    $('next-step').textContent = next;
  }

  /** Says `next` as what to do now (after an error), the step unchanged. */
  hint(next) {
    $('next-step').textContent = next ?? NEXT[this.current];
  }

  /** Says `text` to screen readers (politely). */
  announce(text) {
    const region = $('announce');
    // The same text twice is announced twice: cleared first.
    region.textContent = '';
    setTimeout(() => (region.textContent = text), 30);
  }

  /** Shows the progress of a new job named `label` ('mesh'). */
  start(label) {
    this.label = label;
    this.job = new JobProgress(label, performance.now());
    $('progress').hidden = false;
    this._draw();
    clearInterval(this.timer);
    this.timer = setInterval(() => this._draw(), 500);
    this.announce(`${label} started`);
    $('next-step').textContent = `Working (${label}): wait for it, or press Cancel.`;
  }

  /** A worker report: the bar only moves forward. */
  report(fraction, stage) {
    if (!this.job) return;
    const name = stage && stage !== this.label ? `${this.label}: ${stage}` : this.label;
    if (this.job.report(fraction, name, performance.now()) && stage !== 'done') this.announce(name);
    this._draw();
  }

  /** Hides the progress (the job ended). */
  stop() {
    clearInterval(this.timer);
    this.timer = null;
    this.job = null;
    $('progress').hidden = true;
    $('progress-bar').value = 0;
    $('progress-stage').textContent = '';
    this.hint();
  }

  _draw() {
    const { job } = this;
    if (!job) return;
    const now = performance.now();
    $('progress-bar').value = job.fraction;
    $('progress-bar').dataset.fraction = String(job.fraction);
    $('progress-stage').textContent = job.stage;
    $('progress-time').textContent = job.timeText(now);
  }

  /** Shows `message` as the last error and `next` as what to do; both
   * announced. `actions` ({label, run, testId?}) are buttons under it; with
   * `focus`, the first gets the focus, so the way forward is one key away
   * (not for a mistake said while the user types). */
  error(message, next, actions = [], { focus = false } = {}) {
    $('error').textContent = message;
    $('error').hidden = false;
    const buttons = actions.map(({ label, run, testId }) => {
      const button = document.createElement('button');
      button.type = 'button';
      button.textContent = label;
      if (testId) button.setAttribute('data-testid', testId);
      button.addEventListener('click', run);
      return button;
    });
    $('error-actions').replaceChildren(...buttons);
    $('error-actions').hidden = buttons.length === 0;
    this.hint(next);
    this.announce(`Error: ${message}${next ? ` ${next}` : ''}`);
    if (focus) buttons[0]?.focus({ preventScroll: true });
  }

  clearError() {
    $('error').hidden = true;
    $('error').textContent = '';
    $('error-actions').replaceChildren();
    $('error-actions').hidden = true;
    this.hint();
  }

  /** Says in one line what a change did beyond what was asked, with a
   * button to take it back (`undo`); '' hides it. */
  notice(text, undo = null) {
    $('change-notice-text').textContent = text;
    $('change-notice').hidden = !text;
    $('change-undo').hidden = !undo;
    $('change-undo').onclick = undo
      ? () => {
          this.notice('');
          undo();
        }
      : null;
    if (text) this.announce(text);
  }
}
