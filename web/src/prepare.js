// The Prepare step of the panel, for surfaces that need it before meshing:
// smoothing (auto, off or N passes, with the analysis' note on a voxel
// staircase), repairs and holes (repair.js), and cuts. A closed surface gets the core's proposed cuts at
// its vessel ends (analysis.clip_proposals); the user removes cuts, adds
// one by clicking on a vessel (the core's cutAt: the section perpendicular
// to the vessel there), moves the selected one along the vessel and tilts
// it, then "Cut these open" analyzes the surface again with the cuts as
// clipPlanes, so the openings they make are listed (and named) before
// meshing; meshing uses the same planes (the analyze options). Errors are
// shown here, next to the controls.
import { CutDiscs } from './cut-discs.js';
import { alongVessel, cutPlane, keepSide } from './cut-geometry.js';
import { Repairs } from './repair.js';
import { CLICK_SLOP_PX, listenSurfaceClicks, showClickMode, viewCentre } from './surface-clicks.js';
import { length, point, withUnit } from './units.js';

const $ = (id) => document.getElementById(id);
// A move along the vessel asks the core again at most this far (local
// radii), so the cut follows a bending vessel.
const MOVE_STEP = 0.5;
// Trimming a damaged end, the cut is tried this many opening radii in.
const TRIM_STEPS = [1.5, 2, 3, 4];

const samePlanes = (a, b) => JSON.stringify(a) === JSON.stringify(b);

function element(tag, props = {}, testId = null) {
  const node = Object.assign(document.createElement(tag), props);
  if (testId) node.setAttribute('data-testid', testId);
  return node;
}

/** The analysis' smoothing note, or '' when there is nothing to say. */
export function smoothingNote(s, unit) {
  if (!s) return '';
  const moved = s.applied
    ? `, every vertex within ${length(s.max_displacement_voxels)} voxel of where it was` +
      (Math.abs(s.volume_change) >= 5e-5 ? `, volume ${s.volume_change > 0 ? '+' : ''}${(100 * s.volume_change).toFixed(2)}%` : '')
    : '';
  if (s.staircase) {
    const found = `Voxel staircase detected (voxel ${withUnit(s.voxel, unit)})`;
    return s.applied ? `${found}: smoothed in ${s.passes} passes${moved}.` : `${found}: not smoothed (smoothing off).`;
  }
  if (s.applied) return `Smoothed in ${s.passes} passes, by at most ${withUnit(s.max_displacement, unit)}.`;
  return '';
}

export class Prepare {
  /**
   * @param {object} hooks
   * @param {import('./viewer.js').Viewer} hooks.viewer
   * @param {import('./view-marks.js').ViewMarks} [hooks.marks] where the
   *   repaired places are marked
   * @param {(point: number[]) => Promise<object>} hooks.cutAt the core's cut
   *   across the vessel at the analyzed surface's point nearest `point`:
   *   {ok, point, normal, radius} or {ok: false, error}
   * @param {() => Promise<string|null>} hooks.reanalyze analyzes the surface
   *   again with prepOptions(); resolves the error, or null
   * @param {() => void} hooks.showInput shows the analyzed surface in the view
   * @param {(pending: boolean) => void} [hooks.onChange] the cuts changed;
   *   pending: some are not made yet
   * @param {(what: string) => void} [hooks.onFail] an action of the step
   *   failed (`what`: 'Cut these open'); its message is in #prepare-error
   * @param {() => void} [hooks.onCut] the cuts were made (the openings follow)
   * @param {(text: string) => string} [hooks.words] a core message in the
   *   page's words
   */
  constructor({ viewer, marks, cutAt, reanalyze, showInput, onChange = () => {}, onFail = () => {}, onCut = () => {}, words = (t) => t }) {
    Object.assign(this, { viewer, cutAt, reanalyze, showInput, onChange, onFail, onCut, words });
    this.discs = new CutDiscs(viewer);
    this.cuts = []; // {point, normal, radius, tilt: [a, b] degrees, offset: radii moved, source}
    this.selected = -1;
    this.applied = []; // the clipPlanes of the shown analysis
    this.proposals = [];
    this.fromProposals = false; // the cuts are the proposals, untouched
    this.adding = false;
    this.busy = false;
    this.visible = true; // the analyzed surface is the one shown
    this.moving = null; // the running move along the vessel
    this.unit = 'mm';
    this.scale = 0;
    this.repairs = new Repairs({
      viewer,
      marks,
      reanalyze: () => this._reanalyze(),
      showError: (m) => this._fail(m, 'Repair'),
      showInput: () => this.showInput(),
    });
    this._listen();
  }

  _listen() {
    $('smooth').addEventListener('change', () => {
      $('smooth-passes-field').hidden = $('smooth').value !== 'passes';
      if ($('smooth').value !== 'passes' || this._passes() !== null) this._reanalyze();
    });
    $('smooth-passes').addEventListener('change', () => {
      if (this._passes() !== null) this._reanalyze();
    });
    $('add-cut').addEventListener('click', () => this.setAdding(!this.adding));
    $('cut-center').addEventListener('click', () => this._addAt(...viewCentre(this.viewer)));
    $('propose-cuts').addEventListener('click', () => this._useProposals());
    $('apply-cuts').addEventListener('click', () => this.apply());
    $('cut-move').addEventListener('input', () => this._moveTo(Number($('cut-move').value)));
    for (const [id, k] of [
      ['cut-tilt-a', 0],
      ['cut-tilt-b', 1],
    ]) {
      $(id).addEventListener('input', () => {
        const cut = this.cuts[this.selected];
        if (!cut) return;
        cut.tilt = [...cut.tilt];
        cut.tilt[k] = Number($(id).value);
        this._edited();
      });
    }
    $('cut-deselect').addEventListener('click', () => this.select(-1));

    // A click (not a drag) on the view adds a cut there while adding, else
    // selects the cut drawn there; where the cut would go is said as the
    // pointer moves.
    listenSurfaceClicks($('viewer'), {
      active: () => true,
      onClick: (x, y) => (this.adding ? this._addAt(x, y) : this._selectNear(x, y)),
      onHover: (x, y) => {
        if (this.adding) this._showPick(this.viewer.pick(x, y));
      },
      onEscape: () => {
        if (this.adding) this.setAdding(false);
      },
    });
  }

  /** The passes typed, or null (marked invalid) when not 1-1000. */
  _passes() {
    const input = $('smooth-passes');
    const n = Number(input.value);
    const ok = input.value.trim() !== '' && Number.isInteger(n) && n >= 1 && n <= 1000;
    input.setAttribute('aria-invalid', String(!ok));
    if (!ok) this._fail('Smoothing: the number of passes must be a whole number from 1 to 1000.', 'Smoothing');
    return ok ? n : null;
  }

  /** The analyze options of this step: smooth, repair, holeFraction,
   * clipPlanes (the applied cuts). */
  prepOptions() {
    const prep = this.repairs.prepOptions();
    const mode = $('smooth').value;
    if (mode === 'off') prep.smooth = 'off';
    if (mode === 'passes' && this._passes() !== null) prep.smooth = this._passes();
    if (this.applied.length) prep.clipPlanes = this.applied;
    return prep;
  }

  /** Sets the controls to the analyze options `prep` (those of the shown
   * analysis, or those being tried). */
  showPrep(prep) {
    const smooth = prep.smooth ?? 'auto';
    $('smooth').value = typeof smooth === 'number' ? 'passes' : smooth;
    if (typeof smooth === 'number') $('smooth-passes').value = String(smooth);
    $('smooth-passes-field').hidden = $('smooth').value !== 'passes';
    this.repairs.showPrep(prep);
    this.applied = prep.clipPlanes ?? [];
    this._render();
  }

  /**
   * Shows the step for a new analysis: `fresh` for a new file (the cuts
   * start from the proposals), else the cuts stay (the proposals are
   * taken again when the cuts were the untouched proposals).
   */
  show(analysis, { fresh = false } = {}) {
    this.analysis = analysis;
    this.unit = analysis.units.unit;
    this.scale = analysis.bounding_box.diagonal;
    this.proposals = (analysis.clip_proposals ?? []).map((p) => ({
      point: p.point,
      normal: p.normal,
      radius: p.radius,
      tilt: [0, 0],
      offset: 0,
      source: 'proposal',
    }));
    if (fresh) {
      this.cuts = [];
      this.selected = -1;
      this.fromProposals = false;
      this.clearError();
    }
    if ((fresh || this.fromProposals) && !this.applied.length) {
      this.cuts = this.proposals.map((p) => ({ ...p }));
      this.fromProposals = this.cuts.length > 0;
      this.selected = -1;
    }
    $('smoothing-note').textContent = smoothingNote(analysis.smoothing, this.unit);
    this.repairs.show(analysis);
    this.setAdding(false);
    this._render();
  }

  /** Whether the analyzed surface is the one in the view (the discs show
   * only on it). */
  setVisible(on) {
    this.visible = on;
    this.repairs.setVisible(on);
    if (!on) this.setAdding(false);
    this._draw();
  }

  /** Off while a worker job runs. */
  setBusy(on) {
    this.busy = on;
    this.repairs.setBusy(on);
    this._render();
  }

  showError(message) {
    $('prepare-error').textContent = message;
    $('prepare-error').hidden = false;
  }

  /** Shows the message of a failed action of the step (`what`) here, and
   * tells the page (the bar says what failed and leads here). */
  _fail(message, what) {
    this.showError(this.words(message));
    this.onFail(what);
  }

  clearError() {
    $('prepare-error').hidden = true;
    $('prepare-error').textContent = '';
  }

  /** Turns the "click on a vessel to add a cut" mode on or off. */
  setAdding(on) {
    this.adding = on && !this.busy;
    if (this.adding) this.showInput();
    showClickMode(this.adding, {
      button: 'add-cut',
      centre: 'cut-center',
      onLabel: 'Click on a vessel… (Esc: stop)',
      offLabel: 'Add a cut',
      hint: 'Click on a vessel where it should end',
    });
    if (!this.adding) $('pick-info').textContent = '';
  }

  /** Says where a click would cut (the surface point `at`), or that the
   * pointer is off the surface. */
  _showPick(at) {
    $('pick-info').hidden = false;
    $('pick-info').textContent = at
      ? `Click to cut at ${point(at, this.scale)} ${this.unit}`
      : 'Not on the surface';
  }

  /** Selects the cut whose centre is drawn within CLICK_SLOP_PX * 4 of
   * (x, y), the nearest, if any. */
  _selectNear(x, y) {
    if (!this.visible || this.busy) return;
    let best = -1;
    let bestD = 4 * CLICK_SLOP_PX;
    this.cuts.forEach((cut, i) => {
      const at = this.viewer.screenPoint(cut.point);
      const d = at ? Math.hypot(at[0] - x, at[1] - y) : Infinity;
      if (d < bestD) [best, bestD] = [i, d];
    });
    if (best >= 0) this.select(best);
  }

  /** Why meshing now would not use the listed cuts (they changed since the
   * surface was cut, by the user), or null. */
  pendingProblem() {
    if (this.fromProposals || samePlanes(this.cuts.map(cutPlane), this.applied)) return null;
    return 'Cuts: the listed cuts are not made yet. Press “Cut these open” (or undo the changes) before meshing.';
  }

  /** The listed cuts (copies) and whether they are the untouched
   * proposals: what undo puts back (prep-history.js). */
  cutState() {
    return {
      cuts: this.cuts.map((c) => ({ ...c, point: [...c.point], normal: [...c.normal], tilt: [...c.tilt] })),
      fromProposals: this.fromProposals,
    };
  }

  /** Lists the cuts of a cutState() (none selected, not adding). */
  setCutState({ cuts, fromProposals }) {
    this.cuts = cuts.map((c) => ({ ...c, point: [...c.point], normal: [...c.normal], tilt: [...c.tilt] }));
    this.fromProposals = fromProposals;
    this.selected = -1;
    this.setAdding(false);
    this.clearError();
    this._render();
  }

  /** Moves the focus to the button that makes the cuts. */
  focusApply() {
    $('apply-cuts').focus();
  }

  /** Selects cut i (-1: none) for moving and tilting. */
  select(i) {
    this.selected = i;
    this._render();
    if (i >= 0) {
      $('cut-move').value = String(this.cuts[i].offset);
      [$('cut-tilt-a').value, $('cut-tilt-b').value] = this.cuts[i].tilt.map(String);
      this._showEditValues();
    }
  }

  /** Makes the listed cuts (analyzes again with them as clipPlanes); `focus`: then
   * leads to the openings they made (onCut). The error, or null. */
  async apply({ focus = true } = {}) {
    if (this.busy) return;
    const before = this.applied;
    this.applied = this.cuts.map(cutPlane);
    this.clearError();
    const error = await this.reanalyze();
    if (error) {
      this.applied = before;
      this._fail(`The cuts could not be made: ${error}`, 'Cut these open');
    }
    this._render();
    if (!error && focus) this.onCut();
    return error;
  }

  async _reanalyze() {
    this.clearError();
    const error = await this.reanalyze();
    if (error) this._fail(error, 'The preparation');
  }

  /**
   * Adds a cut across the vessel at each of `points` (the core's cutAt
   * there) and makes the cuts: a remedy's "Cut here" or, with `trim`,
   * "Trim the damaged end" (where the section at the point is no closed
   * loop, the vessel is cut further in: TRIM_STEPS radii from the nearest
   * opening towards the model's middle). A point of a listed or proposed
   * cut (a vessel end) is that cut. The error (also shown here), or null.
   */
  async cutAtPlaces(points, { trim = false } = {}) {
    this.clearError();
    const missed = [];
    const key = (p) => p.map((x) => Number(x).toPrecision(9)).join(',');
    for (const p of points) {
      if (this.cuts.some((c) => key(c.point) === key(p))) continue;
      const proposed = this.proposals.find((c) => key(c.point) === key(p));
      if (proposed) {
        this.cuts.push({ ...proposed });
        continue;
      }
      let found = await this.cutAt(p);
      for (const q of trim ? this._inward(p) : []) {
        if (found.ok) break;
        found = await this.cutAt(q);
      }
      if (!found.ok) {
        missed.push(`${point(p, this.scale)} ${this.unit}: ${found.error}`);
        continue;
      }
      this.cuts.push({ point: found.point, normal: found.normal, radius: found.radius, tilt: [0, 0], offset: 0, source: 'remedy' });
    }
    this.fromProposals = false;
    this.selected = -1;
    this._render();
    if (missed.length === points.length) {
      const error = `No cut there: ${missed.join('; ')}`;
      this._fail(error, 'Cut here');
      return error;
    }
    return this.apply();
  }

  _useProposals() {
    this.cuts = this.proposals.map((p) => ({ ...p }));
    this.fromProposals = true;
    this.selected = -1;
    this._render();
  }

  _remove(i) {
    this.cuts.splice(i, 1);
    if (this.selected === i) this.selected = -1;
    else if (this.selected > i) this.selected--;
    this.fromProposals = false;
    this._render();
    // The focus stays in the table: on the next row's remove button, or the add button.
    const buttons = $('cuts').querySelectorAll('button.cut-remove');
    (buttons[Math.min(i, buttons.length - 1)] ?? $('add-cut')).focus();
  }

  /** Adds the cut across the vessel at the surface point under (x, y). */
  async _addAt(x, y) {
    const at = this.viewer.pick(x, y);
    if (!at) {
      this._fail('No surface there: click on a vessel of the surface.', 'Add a cut');
      return;
    }
    this.clearError();
    const found = await this.cutAt(at);
    if (!found.ok) {
      this._fail(`No cut at ${point(at, this.scale)} ${this.unit}: ${found.error}`, 'Add a cut');
      return;
    }
    const { point: p, normal, radius } = found;
    this.cuts.push({ point: p, normal, radius, tilt: [0, 0], offset: 0, source: 'added' });
    this.fromProposals = false;
    this.setAdding(false);
    this.select(this.cuts.length - 1);
  }

  /** Points on the vessel of the opening nearest `p`, TRIM_STEPS of its
   * radii in from it, towards the middle of the model's box. */
  _inward(p) {
    const openings = this.analysis?.openings ?? [];
    if (!openings.length) return [];
    const far = (o) => Math.hypot(...o.centroid.map((x, k) => x - p[k]));
    const end = openings.reduce((a, b) => (far(b) < far(a) ? b : a));
    const { min, max } = this.analysis.bounding_box;
    const dir = min.map((x, k) => (x + max[k]) / 2 - end.centroid[k]);
    const norm = Math.hypot(...dir) || 1;
    return TRIM_STEPS.map((t) => end.centroid.map((x, k) => x + (dir[k] / norm) * t * end.radius));
  }

  /** Moves the selected cut to `target` radii from where it was placed,
   * asking the core every MOVE_STEP radii (the latest target wins). */
  _moveTo(target) {
    this.moveTarget = target;
    this.moving ??= this._move().finally(() => {
      this.moving = null;
    });
  }

  async _move() {
    const i = this.selected;
    this.clearError();
    while (this.cuts[i] && i === this.selected && this.cuts[i].offset !== this.moveTarget) {
      const cut = this.cuts[i];
      const left = this.moveTarget - cut.offset;
      const step = Math.sign(left) * Math.min(MOVE_STEP, Math.abs(left));
      const found = await this.cutAt(alongVessel(cut, step));
      if (!found.ok) {
        this._fail(`Cut ${i + 1} cannot move further: ${found.error}`, 'Moving the cut');
        if (i === this.selected) $('cut-move').value = String(cut.offset);
        this.moveTarget = cut.offset;
        break;
      }
      const moved = keepSide(found, cut);
      this.cuts[i] = { ...cut, point: moved.point, normal: moved.normal, radius: moved.radius, offset: cut.offset + step };
      this.fromProposals = false;
      this._edited();
    }
  }

  /** A cut changed: the table, the discs and the edit fields follow. */
  _edited() {
    this.fromProposals = false;
    this._render();
    this._showEditValues();
  }

  _showEditValues() {
    const cut = this.cuts[this.selected];
    if (!cut) return;
    const moved = `${cut.offset > 0 ? '+' : ''}${length(cut.offset)}`;
    $('cut-move-value').textContent = `${moved} R`;
    $('cut-move').setAttribute('aria-valuetext', `${moved} local radii`);
    for (const [k, id] of ['cut-tilt-a', 'cut-tilt-b'].entries()) {
      $(`${id}-value`).textContent = `${cut.tilt[k]}°`;
      $(id).setAttribute('aria-valuetext', `${cut.tilt[k]} degrees`);
    }
  }

  _draw() {
    const applied = new Set(this.applied.map((p) => JSON.stringify(p)));
    const made = this.cuts.map((c) => applied.has(JSON.stringify(cutPlane(c))));
    this.discs.show(this.cuts, this.selected, this.visible, made);
  }

  _render() {
    const planes = this.cuts.map(cutPlane);
    const pending = !samePlanes(planes, this.applied);
    const appliedKeys = new Set(this.applied.map((p) => JSON.stringify(p)));
    const rows = this.cuts.map((cut, i) => this._row(cut, i, appliedKeys.has(JSON.stringify(planes[i]))));
    $('cuts').querySelector('tbody').replaceChildren(...rows);
    $('cuts').hidden = rows.length === 0;
    $('cuts-hint').textContent = this._hint(pending);
    const apply = $('apply-cuts');
    apply.textContent = this.applied.length && !this.cuts.length ? 'Remove the cuts' : 'Cut these open';
    apply.hidden = !pending;
    apply.disabled = this.busy;
    $('add-cut').disabled = this.busy;
    $('cut-center').disabled = this.busy;
    const proposals = this.proposals.length > 0 && !samePlanes(planes, this.proposals.map(cutPlane));
    $('propose-cuts').hidden = !proposals;
    $('propose-cuts').disabled = this.busy;
    const cut = this.cuts[this.selected];
    $('cut-edit').hidden = !cut;
    $('cut-edit').disabled = this.busy;
    if (cut) $('cut-edit-title').textContent = `Cut ${this.selected + 1}`;
    this._draw();
    // Pending: listed cuts not made yet (the proposals included).
    this.onChange(pending);
  }

  _hint(pending) {
    const a = this.analysis;
    if (!a) return '';
    const n = this.cuts.length;
    const cuts = (k) => `${k} cut${k === 1 ? '' : 's'}`;
    if (pending && n) {
      const closed = a.closed && !a.openings.length;
      const why = closed ? 'The surface is closed: it must be cut open where the vessels end. ' : '';
      const found = this.fromProposals ? `${cuts(n)} proposed at the vessel ends. ` : '';
      return `${why}${found}Press “Cut these open” to make the openings (${cuts(n)}), or edit the cuts first.`;
    }
    if (pending) return 'No cuts: press “Remove the cuts” to analyze the surface uncut.';
    if (n) return `${cuts(n)} made: each is an opening below. Add, move or remove cuts, then cut again.`;
    if (a.closed && !a.openings.length && this.proposals.length) {
      return `The surface is closed: use the ${cuts(this.proposals.length)} proposed at its vessel ends, or add cuts.`;
    }
    if (a.closed && !a.openings.length) {
      return 'The surface is closed and no vessel ends were found: add a cut on each vessel where it should end.';
    }
    return 'To cut a vessel shorter, or open a closed end, add a cut on it.';
  }

  _row(cut, i, applied) {
    const k = i + 1;
    const tr = element('tr', {}, 'cut-row');
    tr.dataset.state = applied ? 'made' : 'new';
    tr.dataset.source = cut.source;
    tr.classList.toggle('selected', i === this.selected);
    const pick = element('button', { type: 'button', className: 'cut-select', textContent: String(k) }, 'cut-select');
    pick.setAttribute('aria-pressed', String(i === this.selected));
    pick.setAttribute('aria-label', `Select cut ${k} to move or tilt it`);
    pick.disabled = this.busy;
    pick.addEventListener('click', () => this.select(i === this.selected ? -1 : i));
    const remove = element('button', { type: 'button', className: 'cut-remove', textContent: 'Remove' }, 'cut-remove');
    remove.setAttribute('aria-label', `Remove cut ${k}`);
    remove.disabled = this.busy;
    remove.addEventListener('click', () => this._remove(i));
    const cells = [
      pick,
      element('span', { textContent: point(cut.point, this.scale) }),
      element('span', { textContent: length(cut.radius) }),
      element('span', { className: 'cut-state', textContent: applied ? 'made' : 'new' }),
      remove,
    ];
    for (const content of cells) {
      const td = document.createElement('td');
      td.append(content);
      tr.append(td);
    }
    return tr;
  }
}
