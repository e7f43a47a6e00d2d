// "Download report" in the export area: the methods report of the mesh shown
// (the core's report(): one offline HTML page with pictures, histograms,
// parameters, provenance, the family's table after a family), with the
// pictures drawn by the page's own view (report-views.js), downloaded as
// NAME-report.html. The button shows once a mesh exists.
import { baseName } from './files.js';
import { captureReportViews } from './report-views.js';

export class Report {
  /**
   * @param {HTMLButtonElement} button
   * @param {object} hooks
   * @param {import('../../wasm/src/client.js').VesselmeshClient} hooks.client
   * @param {import('./viewer.js').Viewer} hooks.viewer
   * @param {import('./volume-view.js').VolumeView} hooks.volumeView
   * @param {() => ({name: string, result: object} | null)} hooks.mesh the
   *   input's name and the mesh shown, or null
   * @param {() => Promise<boolean>} hooks.ensureMeshed whether the worker
   *   holds that mesh (meshed again when a cancel lost it)
   * @param {() => void} hooks.restoreView shows again what the view showed
   * @param {(stage: string, job: () => Promise<object>) => Promise<object>} hooks.run
   *   runs a worker job with the progress bar
   * @param {(name: string, bytes: Uint8Array, type: string) => void} hooks.download
   * @param {(failure: object) => void} hooks.onFailure
   * @param {(name: string) => void} hooks.onDone
   * @param {(job: () => Promise<void>) => void} hooks.act runs a press, one at a time
   */
  constructor(button, hooks) {
    this.button = button;
    this.box = button.closest('[data-report-box]') ?? button;
    this.hooks = hooks;
    button.addEventListener('click', () => hooks.act(() => this.make()));
  }

  /** Shows the button when there is a mesh to report on. */
  meshed(has) {
    this.box.hidden = !has;
  }

  /** Makes and downloads the report of the mesh shown; its file name, or null. */
  async make() {
    const { hooks } = this;
    if (!hooks.mesh() || !(await hooks.ensureMeshed())) return null;
    const { name, result } = hooks.mesh();
    // Without the view (no WebGL), the core draws the pictures itself.
    const images = await captureReportViews({
      viewer: hooks.viewer,
      volumeView: hooks.volumeView,
      result,
      restore: hooks.restoreView,
    }).catch(() => undefined);
    const made = await hooks.run('report', () => hooks.client.report({ images, inputName: name, mesh: result.handle }));
    if (!made.ok) {
      hooks.onFailure(made);
      return null;
    }
    const file = `${baseName(name)}-report.html`;
    hooks.download(file, made.file, 'text/html');
    hooks.onDone(file);
    return file;
  }
}
