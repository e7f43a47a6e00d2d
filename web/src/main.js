// The vesselmesh page: load a surface file (drop, file picker or generated
// sample: open-file.js), analyze it in the worker (units, caps), show it,
// prepare it (smoothing, cuts: prepare.js), name its openings and set their
// flow extensions, mesh it with the options of the panel (form.js: surface,
// caps, boundary layer, vessel wall, tetrahedra), say whether it is ready
// for CFD and inspect the volume with a clipping plane (result-view.js,
// results.js), export it (export.js: MSH, VTU, VTP, STL, SimVascular
// mesh-complete, OpenFOAM). A refusal comes with its remedy as a button and
// its places marked in the view (problems.js). All meshing happens in the
// Web Worker behind VesselmeshClient, one job at a time (jobs.js), so the
// page stays responsive. This file holds the page's state (the loaded file,
// the mesh shown, what the worker holds) and wires the parts together.
import { VesselmeshClient } from '../../wasm/src/client.js';
import { ActionBar } from './action-bar.js';
import { qualityGradientCss } from './colormap.js';
import { download, exportFile, fillExportFormats, showExportLabel, syncExportFormats, writeOptions } from './export.js';
import { Family } from './family.js';
import { OptionsForm } from './form.js';
import { prepChange } from './history.js';
import { startIsolated } from './isolation.js';
import { Jobs } from './jobs.js';
import { listenOpen, readSurface } from './open-file.js';
import { OpeningWarnings } from './opening-warnings.js';
import { OpeningsTable } from './openings.js';
import { hideAnalysis, showAnalysis } from './panel.js';
import { PrepHistory } from './prep-history.js';
import { Prepare } from './prepare.js';
import { Problems } from './problems.js';
import { applyRemedy } from './remedy-actions.js';
import { Report } from './report.js';
import { resetAll } from './reset.js';
import { ResultView } from './result-view.js';
import { listenShareLink, Settings } from './settings.js';
import { sideEffects, sideEffectText } from './side-effects.js';
import { withUnitGuess } from './units.js';
import { Viewer } from './viewer.js';
import { ViewMarks } from './view-marks.js';
import { listenViewKeys } from './view-keys.js';
import { withPrismsSplit } from './prisms.js';
import { applySolverPreset, showSolverHint } from './solver-preset.js';
import { Refinements } from './refine.js';
import { Measure } from './measure.js';
import { SizeView } from './size-view.js';
import { createWorker } from './worker-source.js';

const $ = (id) => document.getElementById(id);

// Served without COOP/COEP headers, the page reloads once through its
// service worker, which adds them, before the mesher starts (isolation.js).
await startIsolated().catch(() => {});

const client = new VesselmeshClient({ createWorker });
const bar = new ActionBar();
const viewer = new Viewer($('viewer'));
const marks = new ViewMarks(viewer, $('viewer'));
const count = (n) => n.toLocaleString('en');
// { name, bytes, prep, given, analysis, surface, unitGuess, proposals }; prep:
// the analyze options chosen; given: those it was loaded with (a reset
// goes back to them); unitGuess: the first analysis' guess of the unit,
// kept (sent as the unit) until the user chooses one; proposals: the
// vessel ends first proposed to cut.
let current = null;
let remeshed = null; // { key, result } of the last remeshing of `current`
let meshJobs = 0;
// What the worker holds: the surface openingNames() names (its last
// analysis, whose handle is analysisHandle) and the result export() writes
// (its last mesh; the handle is its result's). A failed or cancelled job
// loses them (a cancel restarts the worker). The calls on them name their
// handle rather than rely on the worker's newest.
const held = { analysis: null, analysisHandle: undefined, mesh: null };
const openings = new OpeningsTable($('openings'), {
  openingNames,
  onHover: (loop, k) => {
    viewer.highlightLoop(loop, current.surface.positions);
    marks.activeOpening(k);
  },
  allExtensions: $('flow-all'),
  onColors: (labels) =>
    marks.setOpenings(labels, { onSelect: (k) => openings.select(k), onHover: (k) => openings.highlight(k) }),
});
/** The loaded model's unit and size (the messages' lengths, the marks). */
const model = () => ({ unit: unitName(), scale: current?.analysis.bounding_box.diagonal ?? 1 });
const problems = new Problems({
  bar,
  marks,
  model,
  context: () => ({
    size: form.sizeContext(),
    proposals: (current?.proposals ?? []).map((p) => p.point),
    openings: current?.analysis.openings ?? [],
  }),
  apply: (remedy, stage) => remedyPressed(remedy, stage),
});
const openingChecks = new OpeningWarnings({
  bar,
  problems,
  model,
  apply: (remedy, then) => remedyPressed(remedy, then ? 'mesh' : 'prepare', then),
});
let prepHistory = null; // undo and redo of the preparation (below)
const jobs = new Jobs({
  bar,
  onStart: () => clearError(),
  onBusy: (on) => {
    prepare.setBusy(on);
    refinements.setBusy(on);
    prepHistory.setBusy(on);
  },
});
const { onProgress } = jobs;
const run = (stage, job) => jobs.run(stage, job);
const prepare = new Prepare({
  viewer,
  marks,
  cutAt: (point) =>
    whenAnalyzed('a job is running; try again when it ends', () => client.cutAt(point, { analysis: held.analysisHandle })),
  reanalyze: () => reanalyze({ onError: () => {} }),
  words: (text) => problems.words(text),
  onFail: (what) =>
    problems.text(`“${what}” failed: the message is by the cuts.`, {
      stage: 'prepare',
      next: 'Read the message (Show the message), change the cuts, then try again.',
      panel: $('prepare-error'),
    }),
  onCut: () => $('openings-title').focus(),
  showInput: () => {
    if (!current || view.shown === 'input') return;
    $('show').value = 'input';
    view.show('input', { fit: false });
  },
  // Cuts not made yet: the bar says to make them first.
  onChange: (pending) => {
    prepHistory?.schedule();
    if (bar.current !== 'prepare' || jobs.busy || !$('error').hidden) return;
    bar.hint(pending ? 'Press “Cut these open” to make the listed cuts into openings, then press Mesh.' : undefined);
  },
});

const refinements = new Refinements({
  viewer,
  canPick: () => view.shown !== 'volume',
  showSurface: () => {
    $('show').value = 'input';
    view.show('input', { fit: false });
  },
  onAdding: () => {
    prepare.setAdding(false);
    measure.stop();
  },
  onChange: () => sizeView.optionsChanged(),
});
$('add-cut').addEventListener('click', () => {
  refinements.setAdding(false);
  measure.stop();
});

// The options panel (form.js).
const form = new OptionsForm({
  table: () => client.optionTable,
  current: () => current,
  unitName: () => unitName(),
  layerFractions: (options) => client.layerFractions(options),
  prepare,
  refinements,
  openings,
});

// The size field before meshing (size-view.js) and measurements (measure.js).
const sizeView = new SizeView({
  viewer,
  sizeField: (options) =>
    whenAnalyzed('a job is running; the colours follow when it ends', () =>
      client.sizeField({ ...options, analysis: held.analysisHandle }),
    ),
  sizeOptions: () => form.sizeOptions(),
  surface: () => current?.surface ?? null,
  canColour: () => view.shown === 'input',
  showInput: refinements.showSurface,
});
const measure = new Measure({
  viewer,
  radiusAt: (point) => sizeView.radiusAt(point),
  model: () => current && { unit: current.analysis.units.unit, scale: current.analysis.bounding_box.diagonal },
  canPick: () => view.shown !== 'volume',
  showSurface: () => {
    $('show').value = remeshed ? 'output' : 'input';
    view.show($('show').value, { fit: false });
  },
  onStart: () => {
    prepare.setAdding(false);
    refinements.setAdding(false);
  },
});
for (const id of ['size-mode', 'size-value']) $(id).addEventListener('input', () => sizeView.optionsChanged());
$('size-mode').addEventListener('change', () => sizeView.optionsChanged());

// What the view shows, and the result of a mesh (result-view.js).
const view = new ResultView({
  viewer,
  current: () => current,
  remeshed: () => remeshed,
  meshJobs: () => meshJobs,
  model,
  unitName: () => unitName(),
  client,
  problems,
  openings,
  prepare,
  refinements,
  sizeView,
  showError: (message) => showError(message),
  onMeshed: (result) => {
    report.meshed(true);
    if (!result.family) family.clear();
  },
});

$('legend').querySelector('.ramp').style.background = qualityGradientCss();

// What to do after an error, by what failed.
const NEXT_AFTER = {
  read: 'Open another file (STL, VTP, VTK, OBJ or PLY, or gzipped), or load the sample.',
  mesh: 'Use the button above, or change the options (the size, the cuts, the openings) and press Mesh again.',
  cancelled: 'Cancelled: press the button of the step again when ready.',
  options: 'Correct the field marked in red above, then press Mesh or Export again.',
};

// Undo and redo of the preparation (prep-history.js).
prepHistory = new PrepHistory({
  current: () => current,
  prepare,
  openings,
  reanalyze: (prep, names) => loadBytes(current.name, current.bytes, prep, names),
  isBusy: () => !jobs.idle,
  announce: (text) => bar.announce(text),
});

/** Shows `message` in the action bar with what to do next (`next`: a key of
 * NEXT_AFTER or a text; by default the step's own hint). */
function showError(message, next) {
  if (next === undefined && message === 'Cancelled.') next = 'cancelled';
  problems.text(message, { stage: next === 'read' ? 'read' : 'mesh', next: NEXT_AFTER[next] ?? next });
}

/** Shows a failure of the core (`failure`: {error, remedy?, cancelled?})
 * of `stage` with its remedy; `prefix` says what failed. */
function showFailure(failure, stage, prefix) {
  if (failure.cancelled) showError('Cancelled.', 'cancelled');
  else problems.show(failure, { stage, prefix, next: NEXT_AFTER[stage] });
}

function clearError() {
  problems.clear();
}

/** A remedy's button pressed: applied (remedy-actions.js), one at a time;
 * at the 'mesh' stage, `then` (default: Mesh) goes on after it. */
async function remedyPressed(remedy, stage, then = () => act(remesh)) {
  if (!current || !jobs.idle) return;
  problems.clear();
  document.body.dataset.remedy = 'applying';
  try {
    await applyRemedy(remedy, stage, { prepare, reanalyze, mesh: then });
  } finally {
    document.body.dataset.remedy = 'done';
  }
}

/** Analyzes `bytes` in the worker with the analyze options `prep`; the
 * result, or its error message given to `onError` (default: shown at the
 * top) and returned as { ok: false, message }. */
async function analyze(name, bytes, prep, onError = (message, next, failure) => showFailure(failure, 'read', `${name}: `)) {
  held.analysis = null;
  // The page makes the cuts itself (the Prepare step lists, edits and
  // undoes them), so the core never cuts a blind end the user kept closed.
  const result = await run('read', () => client.analyze(bytes, { ...prep, clip: 'off', onProgress }));
  if (result.ok) {
    held.analysisHandle = result.handle;
    return result;
  }
  const message = result.cancelled ? 'Cancelled.' : `${name}: ${problems.words(result.error)}`;
  onError(message, result.cancelled ? 'cancelled' : 'read', result);
  return { ok: false, message };
}

/** Whether the worker's last analysis is `current`'s (analyzes it again when
 * a failed or cancelled job lost it). */
async function ensureAnalyzed() {
  if (held.analysis === current) return true;
  if (jobs.busy || !(await analyze(current.name, current.bytes, withUnitGuess(current.prep, current.unitGuess))).ok) return false;
  held.analysis = current;
  return true;
}

/** call()'s answer on the analyzed surface, or {ok: false, error} when a job
 * is running (`whileBusy`) or the surface could not be analyzed. */
async function whenAnalyzed(whileBusy, call) {
  if (!jobs.idle) return { ok: false, error: whileBusy };
  if (!(await ensureAnalyzed())) return { ok: false, error: 'the surface could not be analyzed' };
  return call();
}

/** The core's names of the openings (openings.js asks as the user types). */
async function openingNames(options) {
  const here = current;
  if (!(await ensureAnalyzed()) || here !== current) return { ok: false, error: 'not analyzed' };
  return client.openingNames({ ...options, analysis: held.analysisHandle });
}

/**
 * Analyzes and shows a file with the analyze options `prep`; `edits` are
 * opening names the user typed, kept when the same surface is analyzed
 * again in another unit; `fresh` for a new file. On failure the previous
 * file stays, and the error message (given to `onError`) is returned; null
 * on success. The undo history starts again for a new file (unless
 * `keepHistory`), else records the new state.
 */
async function loadBytes(name, bytes, prep = {}, edits = [], { fresh = false, keepHistory = false, onError } = {}) {
  form.showPrep(prep);
  // One guess of the unit a file: the first analysis', sent as the unit
  // again until the user chooses one (a change of smoothing or cuts never
  // changes it silently).
  const guess = fresh ? null : current?.unitGuess ?? null;
  const result = await analyze(name, bytes, withUnitGuess(prep, guess), onError);
  if (!result.ok) {
    if (current) form.showPrep(current.prep);
    return result.message;
  }
  const before = fresh ? null : current;
  const unitGuess = fresh ? (result.analysis.units.guessed ? result.analysis.units : null) : guess;
  if (!prep.units && unitGuess) result.analysis.units = { ...unitGuess };
  const proposals = before ? before.proposals : result.analysis.clip_proposals ?? [];
  // What the file came with (the sample's unit), kept through a reset.
  const given = fresh ? prep : current?.given ?? {};
  current = { name, bytes, prep, given, analysis: result.analysis, surface: result.surface, unitGuess, proposals };
  held.analysis = current;
  if (fresh) bar.notice('');
  if (fresh && !keepHistory && settings.newFile()) {
    bar.notice('A new file: the mesh and export options are back to their defaults (“Keep my settings for the next file” keeps them).');
  }
  if (before && !prepHistory.restoring) announceSideEffects(before, current);
  remeshed = null;
  $('remesh-result').hidden = true;
  report.meshed(false);
  family.clear();
  $('drop-hint').hidden = true;
  $('primary-actions').hidden = false;
  bar.step('prepare');
  bar.announce(`${name} loaded: ${result.analysis.openings.length} openings`);
  $('legend').hidden = false;
  const { analysis } = current;
  showAnalysis(name, analysis, prep);
  form.showUnit(analysis.units.unit);
  const scale = analysis.bounding_box.diagonal;
  openings.show(analysis.openings, { unit: analysis.units.unit, labelArray: analysis.label_array, scale }, edits);
  prepare.show(analysis, { fresh });
  openingChecks.show(analysis, current);
  if (fresh) refinements.reset({ unit: analysis.units.unit, scale });
  measure.stop();
  $('flow-error').hidden = true;
  // The same surface again (other options): the view keeps its camera.
  view.show('input', { fit: fresh || view.shown === null });
  if (fresh && !keepHistory) prepHistory.start();
  else prepHistory.record();
  if (analysis.components > 1) {
    problems.show(
      {
        error: `${name} has ${analysis.components} connected components. ` +
          'Meshing refuses it unless "Keep the largest component only" is checked.',
        remedy: { action: 'largest_component', places: [], value: 0 },
      },
      { stage: 'prepare', next: 'Keep the largest piece (the button below), or open another file.' },
    );
  } else if (fresh && !prep.clipPlanes && current.proposals.length) await openBlindEnds();
  return null;
}

/** A new file's blind vessel ends cut open by default (as the core's clip
 * auto does): the proposed cuts are made and listed, each can be moved or
 * removed (its end kept closed), and Undo takes them all back. */
async function openBlindEnds() {
  const n = current.proposals.length;
  const kept = $('change-notice').hidden ? '' : `${$('change-notice-text').textContent} `;
  if (await prepare.apply({ focus: false })) return;
  const ends = n === 1 ? 'The blind vessel end was' : `The ${n} blind vessel ends were`;
  bar.notice(`${kept}${ends} cut open, 1 local radius in from the tip; remove a cut in Prepare to keep that end closed.`, () =>
    prepHistory.undo(),
  );
}

/** Says in the bar what a preparation change did beyond what was asked
 * (side-effects.js), with Undo. */
function announceSideEffects(before, after) {
  const cause = prepChange({ prep: before.prep }, { prep: after.prep });
  // What the change is for is not a side effect: cuts make openings.
  const expected = { cuts: /^openings /, units: /^units / }[cause];
  const effects = sideEffects(before.analysis, after.analysis).filter((e) => !expected?.test(e));
  bar.notice(sideEffectText(cause, effects), effects.length ? () => prepHistory.undo() : null);
}

/** Analyzes the current file again with the analyze options of the panel;
 * the error message (given to `onError`), or null. */
async function reanalyze({ onError } = {}) {
  if (!current) return null;
  if (!jobs.idle) {
    form.showPrep(current.prep); // a job runs: the controls show what it uses
    return 'a job is running; try again when it ends.';
  }
  const prep = form.prepOptions();
  // Only the unit changed: the same openings, so the typed names stay.
  const surface = (p) => JSON.stringify({ ...p, units: undefined });
  const same = surface(prep) === surface(current.prep);
  return loadBytes(current.name, current.bytes, prep, same ? openings.edits() : [], { onError });
}

/** The unit lengths are given in, in messages. */
const unitName = () => current?.analysis.units.unit ?? 'model units';

async function loadFile(file) {
  if (!jobs.idle) return;
  const read = await readSurface(file);
  if (read.error) {
    showError(read.error, 'read');
    return;
  }
  await loadBytes(file.name, read.bytes, {}, [], { fresh: true });
}

async function loadSample() {
  if (!jobs.idle) return;
  const made = await run('generating sample', () =>
    client.makePhantom({ kind: 'bifurcation', voxel: 0.08, noise: 0.3 }),
  );
  if (!made.ok) {
    showError(made.cancelled ? 'Cancelled.' : `sample: ${made.error}`, made.cancelled ? 'cancelled' : 'read');
    return;
  }
  // The sample is shown in millimetres (a coronary-sized bifurcation, radii
  // 0.6-1 mm): its numbers alone would fit an aorta in cm as well, which is
  // what the core guesses for them.
  await loadBytes('sample-bifurcation.stl', made.stl, { units: 'mm' }, [], { fresh: true });
}

/** The panel's mesh options once every field and opening name is valid
 * (the core checked the names) and the openings look right or the user
 * said to go on (`again`: the press, made again), else null with the
 * problem shown. */
async function checkedMeshOptions(again) {
  const problem = form.problem();
  if (problem) {
    showError(problem, 'options');
    return null;
  }
  const cuts = prepare.pendingProblem();
  if (cuts) {
    showError(cuts, 'Apply the new cuts (Cut these open) or remove them, then press Mesh again.');
    prepare.showError(cuts);
    prepare.focusApply();
    return null;
  }
  if (!(await ensureAnalyzed())) return null;
  const naming = await openings.check();
  if (naming.problem) {
    showError(`Opening ${naming.problem.k}: ${naming.problem.message}`, `Give opening ${naming.problem.k} another name, then press Mesh again.`);
    openings.focusName(naming.problem.k);
    return null;
  }
  if (!openingChecks.allowMesh(again)) return null;
  return form.meshOptions(naming.names);
}

/** Meshes `current` with `options` and `write` (the file to write: format,
 * mshVersion, outputUnits); shows and returns the result, or null. `key`:
 * the panel's options the result stands for (a family's first mesh is the
 * mesh of the options without the family's). */
async function meshWith(options, write = {}, key = JSON.stringify(options)) {
  held.mesh = null;
  document.body.dataset.meshJobs = String(++meshJobs);
  $('flow-error').hidden = true;
  bar.step('mesh');
  const result = await run('mesh', () => client.mesh(current.bytes, { ...options, ...write, onProgress }));
  if (!result.ok) {
    bar.step(remeshed ? 'inspect' : 'prepare');
    showFailure(result, 'mesh', `Mesh failed: ${current.name}: `);
    // A refused flow extension is also said next to the extension fields.
    if (result.option === 'flowExtension' || /flow extension|flowExtension/i.test(result.error)) {
      $('flow-error').textContent = problems.words(result.error);
      $('flow-error').hidden = false;
    }
    return null;
  }
  // Kept prisms are shown as the tetrahedra they split into.
  if (result.volume) result.volume = withPrismsSplit(result.volume);
  remeshed = { key, result };
  held.mesh = remeshed;
  view.showResult(result);
  // A mesh made: the notice of a preparation change (and its Undo) is done
  // with, and would cover the verdict on a phone.
  bar.notice('');
  bar.step('inspect');
  bar.announce(`Meshed: ${count(result.report.output.triangles)} wall triangles`);
  return result;
}

/** Runs a Mesh or Export press, one at a time, with a file loaded. */
async function act(job) {
  if (current) await jobs.act(job);
}

/** Meshes with the panel's options, unless the shown result has them. */
async function remesh() {
  const options = await checkedMeshOptions(() => act(remesh));
  if (options && remeshed?.key !== JSON.stringify(options)) await meshWith(options);
}

/** The Export press (export.js): the worker's last mesh written again when
 * it has the panel's options, else meshed first. */
async function exportPressed() {
  const options = await checkedMeshOptions(() => act(exportPressed));
  if (!options) return;
  await exportFile(options, {
    inputName: () => current.name,
    held: (o) => remeshed?.key === JSON.stringify(o) && held.mesh === remeshed,
    exportHeld: async (format, write) => {
      const result = await run('export', () => client.export(format, { ...write, mesh: remeshed.result.handle }));
      if (!result.ok) showFailure(result, 'mesh', `Export failed: ${current.name}: `);
      return result.ok && result.file;
    },
    meshWith,
    onDone: (name) => {
      bar.step('export', `Exported ${name}. Change the options and press Mesh again, or open another file.`);
      bar.announce(`Exported ${name}`);
    },
  });
}

// The export area's mesh family and methods report (family.js, report.js).
const family = new Family({
  act,
  mesh: async (extra) => {
    const options = await checkedMeshOptions(() => act(() => family.make()));
    return options && meshWith({ ...options, ...extra }, writeOptions(), JSON.stringify(options));
  },
  inputName: () => current.name,
  download,
  showError,
  onDone: (name, { members }) => {
    const next = 'Change the options and mesh again, or open another file.';
    bar.step('export', `Downloaded ${name}: ${members} meshes and their table. ${next}`);
    bar.announce(`Downloaded ${name}`);
  },
});
const report = new Report($('download-report'), {
  act,
  client,
  viewer,
  volumeView: view.volumeView,
  run,
  download,
  mesh: () => remeshed && { name: current.name, result: remeshed.result },
  // A cancel (a new worker) loses the mesh the report is made of: made again.
  ensureMeshed: async () => held.mesh === remeshed || Boolean(await meshWith(JSON.parse(remeshed.key))),
  restoreView: () => view.show(view.shown, { fit: false }),
  onFailure: (failure) => showFailure(failure, 'mesh', `Report failed: ${current.name}: `),
  onDone: (name) => {
    bar.step('export', `Downloaded ${name}. Change the options and press Mesh again, or open another file.`);
    bar.announce(`Downloaded ${name}`);
  },
});

view.listen();
$('format').addEventListener('change', showExportLabel);
form.listen();
$('solver').addEventListener('change', () => applySolverPreset(client.solverPresets, syncExportFormats));
$('surface-only').addEventListener('change', () => {
  form.syncLayerFields();
  syncExportFormats();
});
$('remesh').addEventListener('click', () => act(remesh));
listenOpen({ onFile: loadFile, onSample: loadSample });
$('export').addEventListener('click', () => act(exportPressed));
for (const id of ['units', 'keep-caps', 'largest-component-only']) $(id).addEventListener('change', reanalyze);
for (const button of $('units-prompt').querySelectorAll('button')) {
  button.addEventListener('click', () => {
    $('units').value = button.dataset.unit;
    reanalyze();
  });
}
// A worker whose module ran out of memory was replaced (client.js): it
// holds no analysis nor mesh, as after a cancel.
client.onRestart = () => {
  held.analysis = held.mesh = null;
};
$('cancel').addEventListener('click', () => {
  client.cancel(); // a new worker: it holds no analysis nor mesh
  held.analysis = held.mesh = null;
});
$('fit-view').addEventListener('click', () => viewer.fitView());
// A problem goes once its cause changes: any preparation or mesh option
// edited (not the view's controls, nor the export's), a cut edited.
for (const type of ['input', 'change']) {
  $('summary').addEventListener(type, (e) => {
    if (e.isTrusted && !e.target.closest('#remesh-result, .export, .settings-line')) problems.clear('read');
  });
}
$('prepare').addEventListener('click', (e) => {
  if (e.target.closest('.cut-remove, #propose-cuts, #add-cut')) problems.clear('read');
});
$('change-dismiss').addEventListener('click', () => bar.notice(''));
listenViewKeys(viewer);
$('wireframe').addEventListener('change', (e) => viewer.setWireframe(e.target.checked));

client.ready.then(
  () => {
    showSolverHint(client.solverPresets);
    document.body.setAttribute('data-ready', 'true');
  },
  (e) => showError(`The mesher could not start: ${e.message}`),
);
fillExportFormats();
// The options remembered in this browser (after the export formats exist).
const settings = new Settings({
  onRestore: () => {
    form.showSizeLabel();
    form.syncLayerFields();
    syncExportFormats();
    showSolverHint(client.solverPresets);
  },
});
listenShareLink(settings, settings.restore(), (text) => bar.announce(text));
settings.listen();
$('reset-settings').addEventListener('click', async () => {
  if (!jobs.idle) return;
  const error = await resetAll({
    settings,
    reload: async () => (current ? loadBytes(current.name, current.bytes, current.given, [], { fresh: true, keepHistory: true }) : null),
    fit: () => viewer.fitView(),
  });
  if (!error) bar.announce('Everything reset to the defaults');
});
document.body.dataset.meshJobs = '0';
hideAnalysis();
bar.step('load');
form.syncLayerFields();
syncExportFormats();
