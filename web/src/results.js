// The result part of the panel after meshing: first the verdict (ready for
// CFD, or the things to check, each with a button that shows its places
// in the view: verdict.js), scrolled into sight and focused; then the
// volume's one-line summary, and folded under it the detailed tables and
// histograms (the wall's and the tetrahedra's quality, the surfaces as
// written, the layers), the time, the preset and the y+ sizing.
import { PARTS } from './groups.js';
import { drawHistogram } from './histogram.js';
import { showSurfaceQuality } from './surface-quality.js';
import { presetSettingText } from './solver-preset.js';
import { meshVerdict } from './verdict.js';

const $ = (id) => document.getElementById(id);
const count = (n) => n.toLocaleString('en');

const summaries = new WeakMap();
/** Tetrahedra per part [core, boundary layer, vessel wall] and the volume
 * groups that have tetrahedra, of a result's volume. */
export function volumeSummary(volume) {
  let s = summaries.get(volume);
  if (!s) {
    const parts = [0, 0, 0];
    for (const p of volume.tetPart ?? []) parts[p]++;
    if (!volume.tetPart) parts[0] = volume.tets.length / 4;
    const used = new Set(volume.tetRegion);
    const regions = volume.regionNames.filter((name, i) => name && used.has(i));
    s = { parts, regions };
    summaries.set(volume, s);
  }
  return s;
}

/** The gamma_t histogram: of the core (the layers' elements are flat by
 * design), or of all tetrahedra when asked. */
export function drawTetHistogram(result) {
  const v = result.report.output.volume;
  const { parts } = volumeSummary(result.volume);
  const layered = parts[1] + parts[2] > 0;
  const all = layered && $('tet-histogram-all').checked;
  const core = v.core_quality ?? v.quality;
  let scope = '';
  if (layered) scope = all ? 'of all tetrahedra' : 'of the core (the flat layer elements excluded)';
  $('tet-histogram-scope').textContent = scope;
  const svg = $('tet-histogram');
  svg.dataset.scope = all || !layered ? 'all' : 'core';
  drawHistogram(svg, (all ? v.quality : core).histogram, all ? 'tetrahedra' : 'core tetrahedra');
}

/** One row per grown layer (report.output.volume.boundary_layer and
 * vessel_wall): layers, area with the thickness within 10% of the request,
 * reduced area, front gamma_k min. */
function showLayerStats(v) {
  const pct = (x) => `${(100 * x).toFixed(1)}%`;
  const rows = [
    ['boundary_layer', 'Boundary layer'],
    ['vessel_wall', 'Vessel wall'],
  ].flatMap(([key, label]) => {
    const s = v[key];
    if (!s) return [];
    const tr = document.createElement('tr');
    tr.dataset.part = key;
    const cells = [
      ['name', label],
      ['layers', String(s.layers)],
      ['thickness-within-10pct', pct(s.thickness_within_10pct)],
      ['reduced-area', pct(s.reduced_area_fraction)],
      ['front-quality-min', s.front_quality_min.toFixed(3)],
    ];
    for (const [stat, text] of cells) {
      const td = document.createElement('td');
      td.dataset.stat = stat;
      td.textContent = text;
      tr.append(td);
    }
    return [tr];
  });
  $('layer-stats').querySelector('tbody').replaceChildren(...rows);
  $('layer-stats').hidden = rows.length === 0;
}

/** How long the job took and on how many threads (the browser's cores with
 * the threaded core; one, and why, without it). */
function showTime(seconds, { threads = 1, threadsNote = '' }) {
  const el = $('out-time');
  el.textContent = `Meshed in ${seconds.toFixed(1)} s on ${threads === 1 ? 'one thread' : `${threads} threads`}`;
  el.dataset.threads = String(threads);
  el.title = threads === 1 && threadsNote ? `One thread: ${threadsNote}` : '';
}

/** What the report says of the preset and the y+ sizing, in the result
 * (the preset named as the solver select names it). */
function showPresetAndYplus(report, presets = []) {
  const preset = report.preset;
  $('out-preset').hidden = !preset;
  if (preset) {
    const list = (from) =>
      preset.settings
        .filter((s) => s.from === from)
        .map(presetSettingText)
        .join(', ');
    const yours = list('user');
    const name = presets.find((p) => p.name === preset.solver)?.label ?? preset.solver;
    $('out-preset').textContent = `Preset for ${name}: ${list('preset') || 'nothing'}${yours ? `; yours: ${yours}` : ''}.`;
  }
  const y = report.first_layer_yplus;
  $('out-yplus').hidden = !y;
  if (y) {
    const unit = report.output.unit;
    $('out-yplus').textContent =
      `First layer ${Number(y.height.toPrecision(3))} ${unit} for y+ ${y.yplus} at ${y.inlet} ` +
      `(diameter ${Number(y.inlet_diameter.toPrecision(3))} ${unit}, ${y.inlet_velocity} m/s: ` +
      `Re ${Math.round(y.reynolds)}, τw ${Number(y.wall_shear_stress.toPrecision(3))} Pa).`;
  }
}

/**
 * The verdict's list: one item a line, marked ok (✓), check (!) or note
 * (i), with a "Show" button for the items that have places.
 * @param {(places: object[], options?: {zoom?: boolean, tone?: string,
 *   clip?: boolean}) => void} showPlaces marks the places in the view and
 *   zooms to the first (with clip, the clipping plane through it)
 */
function showVerdict(verdict, showPlaces) {
  const box = $('verdict');
  box.dataset.ready = String(verdict.ready);
  $('verdict-title').textContent = verdict.title;
  const items = verdict.items.map((item) => {
    const li = document.createElement('li');
    li.dataset.level = item.level;
    li.dataset.item = item.id;
    li.setAttribute('data-testid', 'verdict-item');
    const mark = document.createElement('span');
    mark.className = 'verdict-mark';
    mark.textContent = { ok: '✓', check: '!', note: 'i' }[item.level];
    mark.setAttribute('aria-label', { ok: 'fine:', check: 'check:', note: 'note:' }[item.level]);
    mark.setAttribute('role', 'img');
    const text = document.createElement('span');
    text.textContent = item.text;
    li.append(mark, text);
    if (item.places.length) {
      const button = document.createElement('button');
      button.type = 'button';
      button.className = 'verdict-show';
      button.textContent = item.places.length > 1 ? `Show the ${item.places.length} places` : 'Show where';
      button.setAttribute('data-testid', 'verdict-show');
      // A fine item's places (the worst element) are shown as facts, not
      // warnings; a tetrahedron's on the clipping plane.
      const options = { tone: item.level === 'ok' ? 'info' : 'warn', clip: item.id === 'tets' };
      button.addEventListener('click', () => showPlaces(item.places, options));
      li.append(' ', button);
    }
    return li;
  });
  $('verdict-items').replaceChildren(...items);
  // The checks' places are marked at once; the fine items' on request.
  showPlaces(verdict.items.filter((i) => i.level === 'check').flatMap((i) => i.places), { zoom: false });
}

/**
 * Fills the result part of the panel with a mesh result.
 * @param {object} result mesh()'s
 * @param {object} hooks
 * @param {{unit: string, scale: number}} hooks.model the model's unit and size
 * @param {{threads?: number, threadsNote?: string, solverPresets?: object[]}} hooks.client
 * @param {(places: object[], options?: {zoom?: boolean, tone?: string, clip?: boolean}) => void} hooks.showPlaces
 */
export function showMeshResult(result, { model, client, showPlaces }) {
  const out = result.report.output;
  $('out-triangles').textContent = out.triangles.toLocaleString('en');
  $('out-patches').textContent = out.remesh ? out.remesh.patches : '-';
  const decimated = out.remesh?.decimated_triangles ?? 0;
  $('out-decimated').hidden = decimated === 0;
  $('out-decimated-triangles').textContent = decimated.toLocaleString('en');
  // The wall's quality as written (after boundary recovery) when the volume
  // was meshed, else the remeshed surface's (the same file).
  const wall = out.volume?.surfaces?.find((s) => s.name === 'wall')?.quality ?? out.quality;
  $('out-quality-min').textContent = wall.min.toFixed(3);
  $('out-quality-mean').textContent = wall.mean.toFixed(3);
  const fidelity = out.remesh?.fidelity;
  $('out-fidelity').hidden = !fidelity;
  if (fidelity) {
    $('out-far').textContent = fidelity.input_gap_vertices.toLocaleString('en');
    $('out-pinned').textContent = fidelity.pinned_vertices.toLocaleString('en');
  }
  drawHistogram($('out-histogram'), wall.histogram);
  showTime(result.report.seconds, client);
  showPresetAndYplus(result.report, client.solverPresets);
  const elements = out.groups.reduce((n, g) => n + g.elements, 0);
  $('remesh-result').dataset.elements = String(elements);
  const volume = out.volume && result.volume;
  $('volume-result').hidden = !volume;
  $('volume-details').hidden = !volume;
  if (volume) {
    const v = out.volume;
    const { parts } = volumeSummary(result.volume);
    const layered = parts[1] + parts[2] > 0;
    const core = v.core_quality ?? v.quality;
    $('out-tets').textContent = count(v.tetrahedra);
    $('out-parts').textContent = layered
      ? ` (${PARTS.flatMap(({ name }, i) => (parts[i] ? [`${name} ${count(parts[i])}`] : [])).join(', ')})`
      : '';
    $('out-volume-vertices').textContent = count(v.vertices);
    $('out-caps').textContent = out.caps.map((c) => c.name).join(', ') || 'none';
    $('out-tet-min').textContent = core.min.toFixed(3);
    $('out-tet-mean').textContent = core.mean.toFixed(3);
    $('out-tet-all').textContent = layered
      ? `; all tetrahedra min ${v.quality.min.toFixed(3)}, mean ${v.quality.mean.toFixed(3)}`
      : '';
    $('tet-histogram-all-field').hidden = !layered;
    drawTetHistogram(result);
    showLayerStats(v);
    showSurfaceQuality($('surface-quality'), v.surfaces);
  }
  showVerdict(meshVerdict(result, model), showPlaces);
  $('remesh-result').hidden = false;
}

/** Brings the verdict into sight and gives it the focus (after Mesh). */
export function focusVerdict() {
  const box = $('verdict');
  box.scrollIntoView({ block: 'start', behavior: 'instant' });
  box.focus({ preventScroll: true });
}
