// One job at a time: a worker job (read, mesh, export, ...) runs with the
// action bar's progress and Cancel while the controls that would start
// another are off; a press (Mesh, Export, a remedy's, which may run
// several jobs) is handled one at a time.

const $ = (id) => document.getElementById(id);

// Controls that start a job, off while one runs.
const BUSY_CONTROLS = [
  'load-sample',
  'open-file',
  'export',
  'file-input',
  'remesh',
  'units',
  'keep-caps',
  'largest-component-only',
  'smooth',
  'smooth-passes',
  'reset-settings',
  'mesh-family',
  'download-report',
];

export class Jobs {
  /**
   * @param {object} hooks
   * @param {import('./action-bar.js').ActionBar} hooks.bar
   * @param {() => void} hooks.onStart a job starts (the last error goes)
   * @param {(on: boolean) => void} hooks.onBusy the other parts' controls follow
   */
  constructor({ bar, onStart, onBusy }) {
    Object.assign(this, { bar, onStart, onBusy });
    this.busy = false; // a worker job runs (the progress bar is shown)
    this.acting = false; // a press is being handled
    /** A job's progress callback: the bar follows. */
    this.onProgress = (fraction, stage) => bar.report(fraction, stage);
  }

  /** Whether neither a job runs nor a press is handled. */
  get idle() {
    return !this.busy && !this.acting;
  }

  setBusy(on, stage = '') {
    this.busy = on;
    if (on) this.bar.start(stage);
    else this.bar.stop();
    for (const id of BUSY_CONTROLS) $(id).disabled = on;
    for (const button of $('units-prompt').querySelectorAll('button')) button.disabled = on;
    this.onBusy(on);
  }

  /** Runs one worker job with the progress bar; returns its result. */
  async run(stage, job) {
    this.onStart();
    this.setBusy(true, stage);
    try {
      return await job();
    } finally {
      this.setBusy(false);
    }
  }

  /** Runs a press (`job`), unless a job runs or another press is handled. */
  async act(job) {
    if (!this.idle) return;
    this.acting = true;
    try {
      await job();
    } finally {
      this.acting = false;
    }
  }
}
