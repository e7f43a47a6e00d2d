// The vesselmesh page: load a surface file (drop, file picker or generated
// sample), analyze it in the worker (units, caps), show it, prepare it
// (smoothing, cuts: prepare.js), name its openings and set their flow
// extensions, mesh it (surface, caps, boundary layer, vessel wall,
// tetrahedra), say whether it is ready for CFD (results.js), inspect the
// volume with a clipping plane, export it (MSH, VTU, VTP, STL, SimVascular
// mesh-complete). A refusal comes with its remedy as a button and its
// places marked in the view (problems.js). All meshing happens in the Web
// Worker behind VesselmeshClient, so the page stays responsive.
import { VesselmeshClient } from '../../wasm/src/client.js';
import { ActionBar } from './action-bar.js';
import { qualityGradientCss } from './colormap.js';
import { Family } from './family.js';
import { EXPORT_FORMATS, exportFileName, exportFormat } from './files.js';
import { drawGroupLegend, drawPartLegend, foldLegend, PARTS } from './groups.js';
import { prepChange } from './history.js';
import { startIsolated } from './isolation.js';
import { OpeningWarnings } from './opening-warnings.js';
import { OpeningsTable } from './openings.js';
import { hideAnalysis, showAnalysis } from './panel.js';
import { PrepHistory } from './prep-history.js';
import { Prepare } from './prepare.js';
import { Problems } from './problems.js';
import { applyRemedy } from './remedy-actions.js';
import { Report } from './report.js';
import { resetAll } from './reset.js';
import { drawTetHistogram, focusVerdict, showMeshResult, volumeSummary } from './results.js';
import { listenShareLink, Settings } from './settings.js';
import { sideEffects, sideEffectText } from './side-effects.js';
import { describeNonSurface } from './sniff.js';
import { withUnitGuess } from './units.js';
import { Viewer } from './viewer.js';
import { ViewMarks } from './view-marks.js';
import { listenViewKeys } from './view-keys.js';
import { withPrismsSplit } from './prisms.js';
import { applySolverPreset, showSolverHint } from './solver-preset.js';
import { Refinements } from './refine.js';
import { Measure } from './measure.js';
import { SizeView } from './size-view.js';
import { VolumeView } from './volume-view.js';
import { createWorker } from './worker-source.js';

const $ = (id) => document.getElementById(id);
// Above this the browser tab would run out of memory (the wasm heap is 4 GB).
const MAX_FILE_BYTES = 1.5 * 2 ** 30;

// Served without COOP/COEP headers, the page reloads once through its
// service worker, which adds them, before the mesher starts (isolation.js).
await startIsolated().catch(() => {});

const client = new VesselmeshClient({ createWorker });
const bar = new ActionBar();
const viewer = new Viewer($('viewer'));
const marks = new ViewMarks(viewer, $('viewer'));
const count = (n) => n.toLocaleString('en');
const volumeView = new VolumeView(viewer, ({ triangles, cut, cutByPart, ms }) => {
  const box = $('volume-view');
  box.dataset.triangles = String(triangles);
  box.dataset.cut = String(cut);
  [box.dataset.cutCore, box.dataset.cutLayer, box.dataset.cutWall] = cutByPart.map(String);
  const parts = PARTS.flatMap(({ name }, i) => (cutByPart[i] ? [`${count(cutByPart[i])} ${name}`] : []));
  $('clip-info').textContent =
    `${count(triangles)} triangles drawn ` +
    `(${count(cut)} cut faces${parts.length ? `: ${parts.join(', ')}` : ''}) in ${ms.toFixed(1)} ms`;
});
const volumeOption = $('show').querySelector('option[value=volume]');
// { name, bytes, prep, given, analysis, surface, unitGuess, proposals }; prep:
// the analyze options chosen; given: those it was loaded with (a reset
// goes back to them); unitGuess: the first analysis' guess of the unit,
// kept (sent as the unit) until the user chooses one; proposals: the
// vessel ends first proposed to cut.
let current = null;
let remeshed = null; // { key, result } of the last remeshing of `current`
let busy = false; // a worker job runs (the progress bar is shown)
let acting = false; // a Mesh or Export press is being handled
let meshJobs = 0;
let shown = null; // what the view shows: 'input', 'output' or 'volume'
// What the worker holds: the surface openingNames() names (its last
// analysis) and the result export() writes (its last mesh). A failed or
// cancelled job loses them (a cancel restarts the worker).
const held = { analysis: null, mesh: null };
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
    size: { mode: $('size-mode').value, value: numberIn('size-value'), core: numberIn('core-size') },
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
const prepare = new Prepare({
  viewer,
  marks,
  cutAt: (point) => whenAnalyzed('a job is running; try again when it ends', () => client.cutAt(point)),
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
    if (!current || shown === 'input') return;
    $('show').value = 'input';
    show('input', { fit: false });
  },
  // Cuts not made yet: the bar says to make them first.
  onChange: (pending) => {
    prepHistory?.schedule();
    if (bar.current !== 'prepare' || busy || !$('error').hidden) return;
    bar.hint(pending ? 'Press “Cut these open” to make the listed cuts into openings, then press Mesh.' : undefined);
  },
});

const refinements = new Refinements({
  viewer,
  canPick: () => shown !== 'volume',
  showSurface: () => {
    $('show').value = 'input';
    show('input', { fit: false });
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

// The size field before meshing (size-view.js) and measurements (measure.js).
const sizeView = new SizeView({
  viewer,
  sizeField: (options) => whenAnalyzed('a job is running; the colours follow when it ends', () => client.sizeField(options)),
  sizeOptions: () => {
    const refine = refinements.options().filter(([, , , r, h]) => r > 0 && h > 0);
    return { [$('size-mode').value]: numberIn('size-value'), ...(refine.length && { refine }) };
  },
  surface: () => current?.surface ?? null,
  canColour: () => shown === 'input',
  showInput: refinements.showSurface,
});
const measure = new Measure({
  viewer,
  radiusAt: (point) => sizeView.radiusAt(point),
  model: () => current && { unit: current.analysis.units.unit, scale: current.analysis.bounding_box.diagonal },
  canPick: () => shown !== 'volume',
  showSurface: () => {
    $('show').value = remeshed ? 'output' : 'input';
    show($('show').value, { fit: false });
  },
  onStart: () => {
    prepare.setAdding(false);
    refinements.setAdding(false);
  },
});
for (const id of ['size-mode', 'size-value']) $(id).addEventListener('input', () => sizeView.optionsChanged());
$('size-mode').addEventListener('change', () => sizeView.optionsChanged());

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
  isBusy: () => busy || acting,
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
  if (!current || busy || acting) return;
  problems.clear();
  document.body.dataset.remedy = 'applying';
  try {
    await applyRemedy(remedy, stage, { prepare, reanalyze, mesh: then });
  } finally {
    document.body.dataset.remedy = 'done';
  }
}

// Controls that start a job, off while one runs.
const BUSY_CONTROLS = [
  'load-sample',
  'open-file',
  'export',
  'file-input',
  'remesh',
  'units',
  'keep-caps',
  'largest-only',
  'smooth',
  'smooth-passes',
  'reset-settings',
  'mesh-family',
  'download-report',
];

function setBusy(on, stage = '') {
  busy = on;
  if (on) bar.start(stage);
  else bar.stop();
  for (const id of BUSY_CONTROLS) $(id).disabled = on;
  for (const button of $('units-prompt').querySelectorAll('button')) button.disabled = on;
  prepare.setBusy(on);
  refinements.setBusy(on);
  prepHistory.setBusy(on);
}

function onProgress(fraction, stage) {
  bar.report(fraction, stage);
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

/** Analyzes `bytes` in the worker with the analyze options `prep`; the
 * result, or its error message given to `onError` (default: shown at the
 * top) and returned as { ok: false, message }. */
async function analyze(name, bytes, prep, onError = (message, next, failure) => showFailure(failure, 'read', `${name}: `)) {
  held.analysis = null;
  // The page makes the cuts itself (the Prepare step lists, edits and
  // undoes them), so the core never cuts a blind end the user kept closed.
  const result = await run('read', () => client.analyze(bytes, { ...prep, clip: 'off', onProgress }));
  if (result.ok) return result;
  const message = result.cancelled ? 'Cancelled.' : `${name}: ${problems.words(result.error)}`;
  onError(message, result.cancelled ? 'cancelled' : 'read', result);
  return { ok: false, message };
}

/** Whether the worker's last analysis is `current`'s (analyzes it again when
 * a failed or cancelled job lost it). */
async function ensureAnalyzed() {
  if (held.analysis === current) return true;
  if (busy || !(await analyze(current.name, current.bytes, withUnitGuess(current.prep, current.unitGuess))).ok) return false;
  held.analysis = current;
  return true;
}

/** call()'s answer on the analyzed surface, or {ok: false, error} when a job
 * is running (`whileBusy`) or the surface could not be analyzed. */
async function whenAnalyzed(whileBusy, call) {
  if (busy || acting) return { ok: false, error: whileBusy };
  if (!(await ensureAnalyzed())) return { ok: false, error: 'the surface could not be analyzed' };
  return call();
}

/** The core's names of the openings (openings.js asks as the user types). */
async function openingNames(options) {
  const here = current;
  if (!(await ensureAnalyzed()) || here !== current) return { ok: false, error: 'not analyzed' };
  return client.openingNames(options);
}

/** The analyze options chosen in the panel (units, caps, components,
 * smoothing, the cuts made). */
function prepOptions() {
  const prep = prepare.prepOptions();
  if ($('units').value) prep.units = $('units').value;
  if ($('keep-caps').checked) prep.keepCaps = true;
  if ($('largest-only').checked) prep.largestComponentOnly = true;
  return prep;
}

/** Sets the analyze options' controls to `prep`. */
function showPrep(prep) {
  $('units').value = prep.units ?? '';
  $('keep-caps').checked = Boolean(prep.keepCaps);
  $('largest-only').checked = Boolean(prep.largestComponentOnly);
  prepare.showPrep(prep);
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
  showPrep(prep);
  // One guess of the unit a file: the first analysis', sent as the unit
  // again until the user chooses one (a change of smoothing or cuts never
  // changes it silently).
  const guess = fresh ? null : current?.unitGuess ?? null;
  const result = await analyze(name, bytes, withUnitGuess(prep, guess), onError);
  if (!result.ok) {
    if (current) showPrep(current.prep);
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
  showUnit(analysis.units.unit);
  const scale = analysis.bounding_box.diagonal;
  openings.show(analysis.openings, { unit: analysis.units.unit, labelArray: analysis.label_array, scale }, edits);
  prepare.show(analysis, { fresh });
  openingChecks.show(analysis, current);
  if (fresh) refinements.reset({ unit: analysis.units.unit, scale });
  measure.stop();
  $('flow-error').hidden = true;
  // The same surface again (other options): the view keeps its camera.
  show('input', { fit: fresh || shown === null });
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
  if (busy || acting) {
    showPrep(current.prep); // a job runs: the controls show what it uses
    return 'a job is running; try again when it ends.';
  }
  const prep = prepOptions();
  // Only the unit changed: the same openings, so the typed names stay.
  const surface = (p) => JSON.stringify({ ...p, units: undefined });
  const same = surface(prep) === surface(current.prep);
  return loadBytes(current.name, current.bytes, prep, same ? openings.edits() : [], { onError });
}

/** The unit of the current model on every length label of the panel. */
function showUnit(unit) {
  for (const label of document.querySelectorAll('[data-unit-label]')) label.textContent = unit;
  $('output-units').options[0].textContent = `same as input (${unit})`;
  showSizeLabel();
}

/** The unit lengths are given in, in messages. */
const unitName = () => current?.analysis.units.unit ?? 'model units';

/** 'N', or 'h (mm)' for a uniform size. */
function showSizeLabel() {
  $('size-label').textContent = $('size-mode').value === 'size' ? `h (${unitName()})` : 'N';
}

async function loadFile(file) {
  if (busy || acting) return;
  // Not a surface at all (an image, a PDF, an archive, a DICOM slice): said
  // before the core is asked.
  const head = new Uint8Array(await file.slice(0, 512).arrayBuffer().catch(() => new ArrayBuffer(0)));
  const wrong = describeNonSurface(head, file.name);
  if (wrong) {
    showError(`${file.name}: ${wrong}`, 'read');
    return;
  }
  if (file.size > MAX_FILE_BYTES) {
    showError(`${file.name}: file too large (${(file.size / 2 ** 30).toFixed(1)} GB; the limit in a browser tab is 1.5 GB).`, 'read');
    return;
  }
  let bytes;
  try {
    bytes = new Uint8Array(await file.arrayBuffer());
  } catch (e) {
    showError(`${file.name}: cannot read the file (${e.message}).`, 'read');
    return;
  }
  await loadBytes(file.name, bytes, {}, [], { fresh: true });
}

async function loadSample() {
  if (busy || acting) return;
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

function download(name, bytes, type) {
  const url = URL.createObjectURL(new Blob([bytes], { type }));
  const a = document.createElement('a');
  a.href = url;
  a.download = name;
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10_000);
}

/** Marks `input` valid or not; returns `message` when it is not. */
function check(input, ok, message) {
  input.setAttribute('aria-invalid', String(!ok));
  return ok ? null : message;
}

/** The number in a number input (NaN when blank or not a number). */
function numberIn(id) {
  const input = $(id);
  const value = input.value.trim();
  return input.validity.badInput || value === '' ? NaN : Number(value);
}

/**
 * Whether `x` is a valid value of the option with this id, by the core's
 * option table (the worker sends it when ready): its range and, for
 * integers, wholeness. True before the table has arrived (the core checks
 * again).
 */
function fits(id, x) {
  const spec = client.optionTable?.find((s) => s.id === id);
  if (!spec) return true;
  if (!Number.isFinite(x) || (spec.type === 'integer' && !Number.isInteger(x))) return false;
  if (spec.min !== undefined && (spec.minExclusive ? x <= spec.min : x < spec.min)) return false;
  if (spec.max !== undefined && (spec.maxExclusive ? x >= spec.max : x > spec.max)) return false;
  return true;
}

/** What a valid value of the option with this id is, from the table. */
const needs = (id) => client.optionTable?.find((s) => s.id === id)?.needs ?? 'a valid value';

/** Why the core size field is unusable, or null (blank is the default). */
function coreSizeProblem() {
  const input = $('core-size');
  const value = input.value.trim();
  const bad = input.validity.badInput || (value !== '' && !(Number(value) >= 0));
  return check(input, !bad, `Core size must be a length ≥ 0 in ${unitName()}, or blank for the default.`);
}

/** Why the largest volume change field is unusable, or null. */
function volumeChangeProblem() {
  const x = numberIn('max-volume-change');
  return check($('max-volume-change'), x >= 0 && x <= 100, 'Largest volume change must be a percentage from 0 to 100 (Advanced).');
}

const LAYER_FIELDS = [
  'layers',
  'layer-thickness',
  'first-layer',
  'first-layer-yplus',
  'inlet-velocity',
  'density',
  'viscosity',
  'growth',
  'wall-thickness',
  'wall-layers',
];

/** Why the boundary layer or vessel wall fields are unusable: every field
 * that applies is marked, the first problem returned (null when all are
 * fine). */
function layerProblems() {
  for (const id of LAYER_FIELDS) $(id).setAttribute('aria-invalid', 'false');
  if ($('surface-only').checked) return null; // no volume: the fields are unused
  const layers = numberIn('layers') > 0;
  const mode = $('layer-mode').value;
  const first = mode === 'first';
  const yplus = mode === 'yplus';
  const wall = $('wall-on').checked;
  // [field, applies, valid(value), message]
  const rules = [
    ['layers', true, (x) => fits('layers', x), `Boundary layer: the number of layers must be ${needs('layers')}.`],
    [
      'layer-thickness',
      layers && mode === 'thickness',
      (x) => fits('layer_thickness', x),
      `Boundary layer: the total thickness must be ${needs('layer_thickness')} (e.g. 0.2).`,
    ],
    [
      'first-layer',
      layers && first,
      (x) => fits('first_layer', x),
      `Boundary layer: the first-layer height must be ${needs('first_layer')} in ${unitName()}.`,
    ],
    ...[
      ['first-layer-yplus', 'first_layer_yplus', 'the target y+'],
      ['inlet-velocity', 'inlet_velocity', 'the inlet velocity'],
      ['density', 'density', 'the density'],
      ['viscosity', 'viscosity', 'the viscosity'],
    ].map(([id, option, what]) => [
      id,
      layers && yplus,
      (x) => fits(option, x),
      `Boundary layer: ${what} must be ${needs(option)}.`,
    ]),
    ['growth', layers, (x) => fits('growth', x), `Boundary layer: the growth must be ${needs('growth')}.`],
    [
      'wall-thickness',
      wall,
      (x) => fits('wall_thickness', x),
      `Vessel wall: the thickness must be ${needs('wall_thickness')} (e.g. 0.1).`,
    ],
    [
      'wall-layers',
      wall,
      (x) => fits('wall_layers', x) && x >= 1,
      'Vessel wall: the number of layers must be a whole number from 1 (with the wall on).',
    ],
  ];
  const problems = rules
    .filter(([, applies]) => applies)
    .map(([id, , valid, message]) => check($(id), valid(numberIn(id)), message));
  return problems.find(Boolean) ?? null;
}

/** The mesh options chosen in the panel with the opening `names` (without
 * progress and the file to write). */
function meshOptions(names) {
  const mode = $('size-mode').value;
  const options = {
    ...withUnitGuess(current.prep, current.unitGuess),
    clip: 'off', // the cuts are the Prepare step's (analyze())
    ...($('solver').value && { solver: $('solver').value }),
    [mode]: Number($('size-value').value),
    param: $('param').value,
    mesher2d: $('mesher2d').value,
    surfaceOnly: $('surface-only').checked,
  };
  if (!$('fidelity-on').checked) options.fidelity = 0;
  if (!$('decimate-on').checked) options.decimate = 'off';
  const volumeChange = numberIn('max-volume-change') / 100;
  if (volumeChange !== Number($('max-volume-change').defaultValue) / 100) options.maxVolumeChange = volumeChange;
  const coreSize = $('core-size').value.trim();
  if (coreSize !== '') options.coreSize = Number(coreSize);
  const refine = refinements.options();
  if (refine.length) options.refine = refine;
  const flow = openings.flowExtensions();
  if (Object.keys(flow).length) options.flowExtension = flow;
  const inlet = openings.chosenInlet();
  if (inlet !== undefined) options.inlet = inlet;
  if (Object.keys(names).length) options.names = names;
  if (!options.surfaceOnly) {
    options.layers = numberIn('layers');
    if (options.layers > 0) {
      const mode = $('layer-mode').value;
      if (mode === 'first') options.firstLayer = numberIn('first-layer');
      else if (mode === 'yplus') {
        options.firstLayerYplus = numberIn('first-layer-yplus');
        options.inletVelocity = numberIn('inlet-velocity');
        options.density = numberIn('density');
        options.viscosity = numberIn('viscosity');
      } else options.layerThickness = numberIn('layer-thickness');
      options.growth = numberIn('growth');
      options.tagLayer = $('tag-layer').checked;
      options.prisms = $('keep-prisms').checked;
    }
    if ($('wall-on').checked) {
      options.wallThickness = numberIn('wall-thickness');
      options.wallLayers = numberIn('wall-layers');
    }
  }
  return options;
}

/** Enables the layer fields that apply (none with 0 layers or surface only). */
function syncLayerFields() {
  const none = numberIn('layers') === 0;
  const yplusIds = ['first-layer-yplus', 'inlet-velocity', 'density', 'viscosity'];
  for (const id of ['layer-mode', 'layer-thickness', 'first-layer', ...yplusIds, 'growth', 'tag-layer', 'keep-prisms']) {
    $(id).disabled = none;
  }
  const mode = $('layer-mode').value;
  $('layer-thickness-field').hidden = mode !== 'thickness';
  $('first-layer-field').hidden = mode !== 'first';
  $('yplus-fields').hidden = mode !== 'yplus';
  $('wall-thickness').disabled = $('wall-layers').disabled = !$('wall-on').checked;
  $('layer-options').disabled = $('wall-options').disabled = $('surface-only').checked;
}

/**
 * A first-layer height to start from: the first of the current number of
 * layers, growing by the current ratio (the core's layer fractions), that
 * add up to the current total thickness fraction (0.2 if unusable) of the
 * median opening's radius; '' without openings.
 */
async function suggestedFirstLayer() {
  const radii = (current?.analysis.openings ?? []).map((o) => o.radius).sort((a, b) => a - b);
  if (!radii.length) return '';
  const f = numberIn('layer-thickness');
  const total = (fits('layer_thickness', f) ? f : 0.2) * radii[Math.floor(radii.length / 2)];
  const layers = fits('layers', numberIn('layers')) && numberIn('layers') >= 1 ? numberIn('layers') : 4;
  const growth = fits('growth', numberIn('growth')) ? numberIn('growth') : 1;
  const r = await client.layerFractions({ layers, growth });
  return r.ok ? String(Number((total * r.fractions[1]).toPrecision(2))) : '';
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

/** The legends of the volume view: the parts (part colors), the groups
 * (the boundary; with group colors also the volume groups of the cut), the
 * gamma ramp (quality colors). */
function drawLegend(volume) {
  const color = $('volume-color').value;
  const { parts, regions } = volumeSummary(volume);
  $('part-legend').hidden = color !== 'part';
  drawPartLegend($('part-legend'), parts);
  const names = [...volume.surfaceNames, ...(color === 'group' ? regions : [])];
  drawGroupLegend($('group-legend'), names);
  foldLegend($('group-legend-fold'), names.filter(Boolean).length, String(meshJobs));
  $('legend').hidden = color !== 'quality';
}

/** Shows a new mesh: the result part of the panel (its verdict in sight
 * and focused), the caps' names by the openings, the volume in the view. */
function showResult(result) {
  const showPlaces = (places, { zoom = true, tone, clip = false } = {}) => {
    // A place inside the volume: the clipping plane through it, facing the camera.
    if (clip && zoom && shown === 'volume' && places.length) {
      const { axis, position, flip } = volumeView.clipThrough(places[0].point);
      [$('clip-axis').value, $('clip-position').value, $('clip-flip').checked] = [axis, String(position), flip];
    }
    problems.showPlaces(places, '', { zoom, tone });
  };
  showMeshResult(result, { model: model(), client, showPlaces });
  report.meshed(true);
  if (!result.family) family.clear();
  if (result.volume) $('show').prepend(volumeOption);
  else volumeOption.remove();
  openings.showCaps(result.report.output.caps, unitName());
  $('show').value = result.volume ? 'volume' : 'output';
  show($('show').value);
  focusVerdict();
}

/** Shows 'input', 'output' (the remeshed wall) or 'volume' (clipped); a
 * surface is fitted in the view unless fit is false. */
function show(which, { fit = true } = {}) {
  const volume = which === 'volume' ? remeshed?.result.volume : null;
  $('volume-view').hidden = !volume;
  $('group-legend').hidden = $('group-legend-fold').hidden = !volume;
  $('part-legend').hidden = true;
  $('legend').hidden = false;
  if (volume) {
    prepare.setVisible(false);
    refinements.setVisible(false);
    try {
      volumeView.set(volumeOptions());
      volumeView.show(volume);
      drawLegend(volume);
      shown = 'volume';
      sizeView.shown();
      return;
    } catch (e) {
      showError(`Cannot show the volume: ${e.message}`);
      $('volume-view').hidden = $('group-legend').hidden = $('group-legend-fold').hidden = $('part-legend').hidden = true;
      $('legend').hidden = false;
      which = 'output';
      $('show').value = which;
    }
  }
  volumeView.hide();
  const output = which === 'output' && remeshed;
  viewer.setSurface(output ? remeshed.result.surface : current.surface, { fit });
  shown = output ? 'output' : 'input';
  prepare.setVisible(!output);
  refinements.setVisible(true);
  sizeView.shown();
}

/** The panel's mesh options once every field and opening name is valid
 * (the core checked the names) and the openings look right or the user
 * said to go on (`again`: the press, made again), else null with the
 * problem shown. */
async function checkedMeshOptions(again) {
  const problem = [coreSizeProblem(), volumeChangeProblem(), refinements.problem(), layerProblems(), openings.extensionProblem()].find(Boolean);
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
  return meshOptions(naming.names);
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
  showResult(result);
  // A mesh made: the notice of a preparation change (and its Undo) is done
  // with, and would cover the verdict on a phone.
  bar.notice('');
  bar.step('inspect');
  bar.announce(`Meshed: ${count(result.report.output.triangles)} wall triangles`);
  return result;
}

/** Runs a Mesh or Export press, one at a time. */
async function act(job) {
  if (!current || busy || acting) return;
  acting = true;
  try {
    await job();
  } finally {
    acting = false;
  }
}

/** Meshes with the panel's options, unless the shown result has them. */
async function remesh() {
  const options = await checkedMeshOptions(() => act(remesh));
  if (options && remeshed?.key !== JSON.stringify(options)) await meshWith(options);
}

/** The chosen file format and units to write: export() and mesh() options. */
function writeOptions() {
  const { format, mshVersion } = exportFormat($('export-format').value);
  const outputUnits = $('output-units').value;
  return { format, ...(mshVersion && { mshVersion }), ...(outputUnits && { outputUnits }) };
}

/**
 * Downloads the mesh in the chosen format: written again from the worker's
 * last mesh when it has the panel's options (no meshing), else meshed first.
 */
async function exportFile() {
  const options = await checkedMeshOptions(() => act(exportFile));
  if (!options) return;
  const { format, ...write } = writeOptions();
  let file;
  if (remeshed?.key === JSON.stringify(options) && held.mesh === remeshed) {
    const result = await run('export', () => client.export(format, write));
    if (!result.ok) showFailure(result, 'mesh', `Export failed: ${current.name}: `);
    file = result.ok && result.file;
  } else {
    file = (await meshWith(options, { format, ...write }))?.file;
  }
  const chosen = exportFormat($('export-format').value);
  if (file) {
    const name = exportFileName(current.name, chosen.value);
    download(name, file, chosen.mime);
    bar.step('export', `Exported ${name}. Change the options and press Mesh again, or open another file.`);
    bar.announce(`Exported ${name}`);
  }
}

/** The export formats that apply: a surface-only mesh has no volume formats. */
function syncExportFormats() {
  const surfaceOnly = $('surface-only').checked;
  for (const option of $('export-format').options) {
    option.disabled = surfaceOnly && exportFormat(option.value).volume === true;
  }
  if ($('export-format').selectedOptions[0]?.disabled) $('export-format').value = EXPORT_FORMATS[0].value;
  $('export-hint').hidden = !surfaceOnly;
  showExportLabel();
}

/** The Export button names the chosen format: 'Export MSH 4.1'. */
function showExportLabel() {
  const { label } = exportFormat($('export-format').value);
  $('export').textContent = `Export ${label.replace(/ \(.*\)$/, '')}`;
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
  volumeView,
  run,
  download,
  mesh: () => remeshed && { name: current.name, result: remeshed.result },
  // A cancel (a new worker) loses the mesh the report is made of: made again.
  ensureMeshed: async () => held.mesh === remeshed || Boolean(await meshWith(JSON.parse(remeshed.key))),
  restoreView: () => show(shown, { fit: false }),
  onFailure: (failure) => showFailure(failure, 'mesh', `Report failed: ${current.name}: `),
  onDone: (name) => {
    bar.step('export', `Downloaded ${name}. Change the options and press Mesh again, or open another file.`);
    bar.announce(`Downloaded ${name}`);
  },
});

$('size-mode').addEventListener('change', (e) => {
  const uniform = e.target.value === 'size';
  showSizeLabel();
  // A sensible start: 2 pi R / 20 of the median opening, or a 50th of the box.
  const radii = (current?.analysis.openings ?? []).map((o) => o.radius).sort((a, b) => a - b);
  const diag = current?.analysis.bounding_box.diagonal ?? 1;
  const h = radii.length ? (2 * Math.PI * radii[Math.floor(radii.length / 2)]) / 20 : diag / 50;
  $('size-value').value = uniform ? Number(h.toPrecision(2)) : 20;
});
$('show').addEventListener('change', (e) => show(e.target.value));
$('export-format').addEventListener('change', showExportLabel);
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
for (const id of ['core-size', 'max-volume-change', ...LAYER_FIELDS]) {
  $(id).addEventListener('input', () => $(id).setAttribute('aria-invalid', 'false'));
}
$('layers').addEventListener('input', syncLayerFields);
$('layer-mode').addEventListener('change', (e) => {
  if (e.target.value === 'first' && $('first-layer').value.trim() === '') {
    suggestedFirstLayer().then((h) => {
      if ($('first-layer').value.trim() === '') $('first-layer').value = h;
    });
  }
  syncLayerFields();
});
$('wall-on').addEventListener('change', syncLayerFields);
$('solver').addEventListener('change', () => applySolverPreset(client.solverPresets, syncExportFormats));
$('surface-only').addEventListener('change', () => {
  syncLayerFields();
  syncExportFormats();
});
$('tet-histogram-all').addEventListener('change', () => {
  if (remeshed?.result.volume) drawTetHistogram(remeshed.result);
});
$('remesh').addEventListener('click', () => act(remesh));
$('file-input').addEventListener('change', (e) => {
  const file = e.target.files[0];
  e.target.value = '';
  if (file) loadFile(file);
});
$('load-sample').addEventListener('click', loadSample);
$('open-file').addEventListener('click', () => $('file-input').click());
$('export').addEventListener('click', () => act(exportFile));
for (const id of ['units', 'keep-caps', 'largest-only']) $(id).addEventListener('change', reanalyze);
for (const button of $('units-prompt').querySelectorAll('button')) {
  button.addEventListener('click', () => {
    $('units').value = button.dataset.unit;
    reanalyze();
  });
}
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
  () => {
    showSolverHint(client.solverPresets);
    family.configure(client.optionTable);
    document.body.setAttribute('data-ready', 'true');
  },
  (e) => showError(`The mesher could not start: ${e.message}`),
);
$('export-format').replaceChildren(...EXPORT_FORMATS.map(({ value, label }) => new Option(label, value)));
// The options remembered in this browser (after the export formats exist).
const settings = new Settings({
  onRestore: () => {
    showSizeLabel();
    syncLayerFields();
    syncExportFormats();
    showSolverHint(client.solverPresets);
  },
});
listenShareLink(settings, settings.restore(), (text) => bar.announce(text));
settings.listen();
$('reset-settings').addEventListener('click', async () => {
  if (busy || acting) return;
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
syncLayerFields();
syncExportFormats();
