// What is shown after a mesh: the result part of the panel (results.js)
// with its verdict in sight, the caps' names by the openings, and in the
// view the volume clipped by a plane (volume-view.js), the remeshed wall or
// the input surface, as the Show select says; the clipping plane's
// controls, the legends of the volume (parts, groups, quality) and the
// numbers of what is drawn.
import { drawGroupLegend, drawPartLegend, foldLegend, PARTS } from './groups.js';
import { drawTetHistogram, focusVerdict, showMeshResult, volumeSummary } from './results.js';
import { VolumeView } from './volume-view.js';

const $ = (id) => document.getElementById(id);
const count = (n) => n.toLocaleString('en');

/** The clipping options chosen in the panel. */
function volumeOptions() {
  return {
    axis: $('clip-axis').value,
    position: Number($('clip-position').value),
    flip: $('clip-flip').checked,
    color: $('volume-color').value,
    boundary: $('show-boundary').checked,
    edges: $('show-edges').checked,
  };
}

export class ResultView {
  /**
   * @param {object} hooks
   * @param {import('./viewer.js').Viewer} hooks.viewer
   * @param {() => object|null} hooks.current the loaded file ({surface, name})
   * @param {() => object|null} hooks.remeshed the shown mesh ({key, result}), or null
   * @param {() => number} hooks.meshJobs how many meshes were asked for (a legend's fold follows it)
   * @param {() => {unit: string, scale: number}} hooks.model the model's unit and size
   * @param {() => string} hooks.unitName
   * @param {object} hooks.client the worker's client (results.js asks it)
   * @param {import('./problems.js').Problems} hooks.problems marks places in the view
   * @param {import('./openings.js').OpeningsTable} hooks.openings
   * @param {(message: string) => void} hooks.showError
   * @param {(result: object) => void} hooks.onMeshed a new mesh is shown (the report and family follow)
   * @param {import('./prepare.js').Prepare} hooks.prepare its cuts shown on the input only
   * @param {import('./refine.js').Refinements} hooks.refinements shown on a surface only
   * @param {import('./size-view.js').SizeView} hooks.sizeView told what is shown
   */
  constructor(hooks) {
    this.hooks = hooks;
    /** What the view shows: 'input', 'output' or 'volume' (null before a file). */
    this.shown = null;
    this.volumeOption = $('show').querySelector('option[value=volume]');
    this.volumeView = new VolumeView(hooks.viewer, ({ triangles, cut, cutByPart, ms }) => {
      const box = $('volume-view');
      box.dataset.triangles = String(triangles);
      box.dataset.cut = String(cut);
      [box.dataset.cutCore, box.dataset.cutLayer, box.dataset.cutWall] = cutByPart.map(String);
      const parts = PARTS.flatMap(({ name }, i) => (cutByPart[i] ? [`${count(cutByPart[i])} ${name}`] : []));
      $('clip-info').textContent =
        `${count(triangles)} triangles drawn ` +
        `(${count(cut)} cut faces${parts.length ? `: ${parts.join(', ')}` : ''}) in ${ms.toFixed(1)} ms`;
    });
  }

  /** The legends of the volume view: the parts (part colors), the groups
   * (the boundary; with group colors also the volume groups of the cut), the
   * gamma ramp (quality colors). */
  drawLegend(volume) {
    const color = $('volume-color').value;
    const { parts, regions } = volumeSummary(volume);
    $('part-legend').hidden = color !== 'part';
    drawPartLegend($('part-legend'), parts);
    const names = [...volume.surfaceNames, ...(color === 'group' ? regions : [])];
    drawGroupLegend($('group-legend'), names);
    foldLegend($('group-legend-fold'), names.filter(Boolean).length, String(this.hooks.meshJobs()));
    $('legend').hidden = color !== 'quality';
  }

  /** Shows a new mesh: the result part of the panel (its verdict in sight
   * and focused), the caps' names by the openings, the volume in the view. */
  showResult(result) {
    const { client, problems, openings } = this.hooks;
    const showPlaces = (places, { zoom = true, tone, clip = false } = {}) => {
      // A place inside the volume: the clipping plane through it, facing the camera.
      if (clip && zoom && this.shown === 'volume' && places.length) {
        const { axis, position, flip } = this.volumeView.clipThrough(places[0].point);
        [$('clip-axis').value, $('clip-position').value, $('clip-flip').checked] = [axis, String(position), flip];
      }
      problems.showPlaces(places, '', { zoom, tone });
    };
    showMeshResult(result, { model: this.hooks.model(), client, showPlaces });
    this.hooks.onMeshed(result);
    if (result.volume) $('show').prepend(this.volumeOption);
    else this.volumeOption.remove();
    openings.showCaps(result.report.output.caps, this.hooks.unitName());
    $('show').value = result.volume ? 'volume' : 'output';
    this.show($('show').value);
    focusVerdict();
  }

  /** Shows 'input', 'output' (the remeshed wall) or 'volume' (clipped); a
   * surface is fitted in the view unless fit is false. */
  show(which, { fit = true } = {}) {
    const { viewer, prepare, refinements, sizeView } = this.hooks;
    const remeshed = this.hooks.remeshed();
    const volume = which === 'volume' ? remeshed?.result.volume : null;
    $('volume-view').hidden = !volume;
    $('group-legend').hidden = $('group-legend-fold').hidden = !volume;
    $('part-legend').hidden = true;
    $('legend').hidden = false;
    if (volume) {
      prepare.setVisible(false);
      refinements.setVisible(false);
      try {
        this.volumeView.set(volumeOptions());
        this.volumeView.show(volume);
        this.drawLegend(volume);
        this.shown = 'volume';
        sizeView.shown();
        return;
      } catch (e) {
        this.hooks.showError(`Cannot show the volume: ${e.message}`);
        $('volume-view').hidden = $('group-legend').hidden = $('group-legend-fold').hidden = $('part-legend').hidden = true;
        $('legend').hidden = false;
        which = 'output';
        $('show').value = which;
      }
    }
    this.volumeView.hide();
    const output = which === 'output' && remeshed;
    viewer.setSurface(output ? remeshed.result.surface : this.hooks.current().surface, { fit });
    this.shown = output ? 'output' : 'input';
    prepare.setVisible(!output);
    refinements.setVisible(true);
    sizeView.shown();
  }

  /** Follows the Show select, the clipping plane's controls and the
   * histogram's scope. */
  listen() {
    const { volumeView } = this;
    $('show').addEventListener('change', (e) => this.show(e.target.value));
    $('clip-axis').addEventListener('change', (e) => {
      // A new normal keeps the side away from the camera: the cut faces you.
      const axis = e.target.value;
      $('clip-flip').checked = volumeView.flipFacingCamera(axis);
      volumeView.set({ axis, flip: $('clip-flip').checked });
    });
    $('clip-position').addEventListener('input', (e) => volumeView.set({ position: Number(e.target.value) }));
    $('clip-flip').addEventListener('change', (e) => volumeView.set({ flip: e.target.checked }));
    $('volume-color').addEventListener('change', (e) => {
      volumeView.set({ color: e.target.value });
      const volume = this.hooks.remeshed()?.result.volume;
      if (volume) this.drawLegend(volume);
    });
    $('show-boundary').addEventListener('change', (e) => volumeView.set({ boundary: e.target.checked }));
    $('show-edges').addEventListener('change', (e) => volumeView.set({ edges: e.target.checked }));
    $('tet-histogram-all').addEventListener('change', () => {
      const result = this.hooks.remeshed()?.result;
      if (result?.volume) drawTetHistogram(result);
    });
  }
}
