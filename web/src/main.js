// The vesselmesh page: load an STL (drop, file picker or generated sample),
// analyze it in the worker, show it, mesh it (surface, caps, tetrahedra),
// inspect the volume with a clipping plane, export MSH. All meshing happens
// in the Web Worker behind VesselmeshClient, so the page stays responsive.
import { VesselmeshClient } from '../../wasm/src/client.js';
import { qualityGradientCss } from './colormap.js';
import { drawGroupLegend } from './groups.js';
import { drawHistogram } from './histogram.js';
import { chosenInlet, hideAnalysis, showAnalysis, showCaps } from './panel.js';
import { Viewer } from './viewer.js';
import { VolumeView } from './volume-view.js';

const $ = (id) => document.getElementById(id);
// Above this the browser tab would run out of memory (the wasm heap is 4 GB).
const MAX_FILE_BYTES = 1.5 * 2 ** 30;

const client = new VesselmeshClient();
const viewer = new Viewer($('viewer'));
const volumeView = new VolumeView(viewer, ({ triangles, cut, ms }) => {
  const box = $('volume-view');
  box.dataset.triangles = String(triangles);
  box.dataset.cut = String(cut);
  $('clip-info').textContent =
    `${triangles.toLocaleString('en')} triangles drawn ` +
    `(${cut.toLocaleString('en')} cut faces) in ${ms.toFixed(1)} ms`;
});
const volumeOption = $('show').querySelector('option[value=volume]');
let current = null; // { name, bytes, analysis, surface }
let remeshed = null; // { key, result } of the last remeshing of `current`
let busy = false;

$('legend').querySelector('.ramp').style.background = qualityGradientCss();

function showError(message) {
  $('error').textContent = message;
  $('error').hidden = false;
}

function clearError() {
  $('error').hidden = true;
  $('error').textContent = '';
}

function setBusy(on, stage = '') {
  busy = on;
  $('progress').hidden = !on;
  $('progress-bar').value = 0;
  $('progress-stage').textContent = stage;
  for (const id of ['load-sample', 'export-msh', 'file-input', 'remesh']) $(id).disabled = on;
}

function onProgress(fraction, stage) {
  $('progress-bar').value = fraction;
  $('progress-stage').textContent = stage;
}

/** Runs one worker job with the progress bar; returns its result. */
async function run(stage, job) {
  clearError();
  setBusy(true, stage);
  try {
    return await job();
  } finally {
    setBusy(false);
  }
}

async function loadBytes(name, bytes) {
  const result = await run('read', () => client.analyze(bytes, { onProgress }));
  if (!result.ok) {
    showError(result.cancelled ? 'Cancelled.' : `${name}: ${result.error}`);
    return;
  }
  current = { name, bytes, analysis: result.analysis, surface: result.surface };
  remeshed = null;
  $('remesh-result').hidden = true;
  $('drop-hint').hidden = true;
  $('legend').hidden = false;
  const hover = (loop) => viewer.highlightLoop(loop, current.surface.positions);
  showAnalysis(name, result.analysis, hover);
  show('input');
  if (result.analysis.components > 1) {
    showError(
      `${name} has ${result.analysis.components} connected components. ` +
        'Export refuses it unless "Keep the largest component only" is checked.',
    );
  }
}

async function loadFile(file) {
  if (busy) return;
  if (file.size > MAX_FILE_BYTES) {
    showError(`${file.name}: file too large (${(file.size / 2 ** 30).toFixed(1)} GB; the limit in a browser tab is 1.5 GB).`);
    return;
  }
  let bytes;
  try {
    bytes = new Uint8Array(await file.arrayBuffer());
  } catch (e) {
    showError(`${file.name}: cannot read the file (${e.message}).`);
    return;
  }
  await loadBytes(file.name, bytes);
}

async function loadSample() {
  if (busy) return;
  const made = await run('generating sample', () =>
    client.makePhantom({ kind: 'bifurcation', voxel: 0.08, noise: 0.3 }),
  );
  if (!made.ok) {
    showError(made.cancelled ? 'Cancelled.' : `sample: ${made.error}`);
    return;
  }
  await loadBytes('sample-bifurcation.stl', made.stl);
}

function download(name, bytes) {
  const url = URL.createObjectURL(new Blob([bytes], { type: 'text/plain' }));
  const a = document.createElement('a');
  a.href = url;
  a.download = name;
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10_000);
}

/** Why the core size field is unusable, or null (blank is the default). */
function coreSizeProblem() {
  const input = $('core-size');
  const value = input.value.trim();
  const bad = input.validity.badInput || (value !== '' && !(Number(value) >= 0));
  input.setAttribute('aria-invalid', String(bad));
  return bad ? 'Core size must be a length ≥ 0 in model units, or blank for the default.' : null;
}

/** The mesh options chosen in the panel (without progress). */
function meshOptions() {
  const mode = $('size-mode').value;
  const options = {
    mshVersion: $('msh-version').value,
    largestComponentOnly: $('largest-only').checked,
    [mode]: Number($('size-value').value),
    param: $('param').value,
    mesher2d: $('mesher2d').value,
    surfaceOnly: $('surface-only').checked,
  };
  const coreSize = $('core-size').value.trim();
  if (coreSize !== '') options.coreSize = Number(coreSize);
  const inlet = chosenInlet();
  if (inlet !== undefined) options.inlet = inlet;
  return options;
}

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

function drawLegend(volume) {
  const names = [...volume.surfaceNames];
  if ($('volume-color').value === 'group') names.push('lumen');
  drawGroupLegend($('group-legend'), names);
}

/** Shows 'input', 'output' (the remeshed wall) or 'volume' (clipped). */
function show(which) {
  const volume = which === 'volume' ? remeshed?.result.volume : null;
  $('volume-view').hidden = !volume;
  $('group-legend').hidden = !volume;
  if (volume) {
    try {
      volumeView.set(volumeOptions());
      volumeView.show(volume);
      drawLegend(volume);
      return;
    } catch (e) {
      showError(`Cannot show the volume: ${e.message}`);
      $('volume-view').hidden = $('group-legend').hidden = true;
      which = 'output';
      $('show').value = which;
    }
  }
  volumeView.hide();
  viewer.setSurface(which === 'output' && remeshed ? remeshed.result.surface : current.surface);
}

/** Fills the result part of the panel with a mesh result. */
function showMeshResult(result) {
  const out = result.report.output;
  $('out-triangles').textContent = out.triangles.toLocaleString('en');
  $('out-patches').textContent = out.remesh ? out.remesh.patches : '-';
  $('out-quality-min').textContent = out.quality.min.toFixed(3);
  $('out-quality-mean').textContent = out.quality.mean.toFixed(3);
  drawHistogram($('out-histogram'), out.quality.histogram);
  const elements = out.groups.reduce((n, g) => n + g.elements, 0);
  $('remesh-result').dataset.elements = String(elements);
  const volume = out.volume && result.volume;
  $('volume-result').hidden = !volume;
  if (volume) {
    $('out-tets').textContent = out.volume.tetrahedra.toLocaleString('en');
    $('out-volume-vertices').textContent = out.volume.vertices.toLocaleString('en');
    $('out-caps').textContent = out.caps.map((c) => c.name).join(', ') || 'none';
    $('out-tet-min').textContent = out.volume.quality.min.toFixed(3);
    $('out-tet-mean').textContent = out.volume.quality.mean.toFixed(3);
    drawHistogram($('tet-histogram'), out.volume.quality.histogram, 'tetrahedra');
    $('show').prepend(volumeOption);
  } else {
    volumeOption.remove();
  }
  showCaps(current.analysis.openings, out.caps);
  $('remesh-result').hidden = false;
  $('show').value = volume ? 'volume' : 'output';
  show($('show').value);
}

/** Meshes `current` with the panel's options, reusing the last result. */
async function meshCurrent() {
  const problem = coreSizeProblem();
  if (problem) {
    showError(problem);
    return null;
  }
  const options = meshOptions();
  const key = JSON.stringify(options);
  if (remeshed?.key === key) return remeshed.result;
  const result = await run('mesh', () => client.mesh(current.bytes, { ...options, onProgress }));
  if (!result.ok) {
    showError(result.cancelled ? 'Cancelled.' : `${current.name}: ${result.error}`);
    return null;
  }
  remeshed = { key, result };
  showMeshResult(result);
  return result;
}

async function remesh() {
  if (!current || busy) return;
  await meshCurrent();
}

async function exportMsh() {
  if (!current || busy) return;
  const result = await meshCurrent();
  if (result) download(current.name.replace(/\.stl$/i, '') + '.msh', result.msh);
}

$('size-mode').addEventListener('change', (e) => {
  const uniform = e.target.value === 'size';
  $('size-label').textContent = uniform ? 'h' : 'N';
  // A sensible start: 2 pi R / 20 of the median opening, or a 50th of the box.
  const openings = current?.analysis.openings ?? [];
  const radii = openings.map((o) => o.radius).sort((a, b) => a - b);
  const diag = current?.analysis.bounding_box.diagonal ?? 1;
  const h = radii.length ? (2 * Math.PI * radii[Math.floor(radii.length / 2)]) / 20 : diag / 50;
  $('size-value').value = uniform ? Number(h.toPrecision(2)) : 20;
});
$('show').addEventListener('change', (e) => show(e.target.value));
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
  if (remeshed?.result.volume) drawLegend(remeshed.result.volume);
});
$('show-boundary').addEventListener('change', (e) => volumeView.set({ boundary: e.target.checked }));
$('show-edges').addEventListener('change', (e) => volumeView.set({ edges: e.target.checked }));
$('core-size').addEventListener('input', () => $('core-size').setAttribute('aria-invalid', 'false'));
$('remesh').addEventListener('click', remesh);
$('file-input').addEventListener('change', (e) => {
  const file = e.target.files[0];
  e.target.value = '';
  if (file) loadFile(file);
});
$('load-sample').addEventListener('click', loadSample);
$('export-msh').addEventListener('click', exportMsh);
$('cancel').addEventListener('click', () => client.cancel());
$('fit-view').addEventListener('click', () => viewer.fitView());
$('wireframe').addEventListener('change', (e) => viewer.setWireframe(e.target.checked));

const view = $('viewer');
view.addEventListener('dragover', (e) => {
  e.preventDefault();
  view.classList.add('dragging');
});
view.addEventListener('dragleave', () => view.classList.remove('dragging'));
view.addEventListener('drop', (e) => {
  e.preventDefault();
  view.classList.remove('dragging');
  const file = e.dataTransfer.files[0];
  if (file) loadFile(file);
});

client.ready.then(
  () => document.body.setAttribute('data-ready', 'true'),
  (e) => showError(`The mesher could not start: ${e.message}`),
);
hideAnalysis();
