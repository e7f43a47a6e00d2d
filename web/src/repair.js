// The repairs of the Prepare step: the repair mode (auto: make the surface
// manifold and close small holes; off: only the safe repairs) and the hole
// size (a boundary loop whose equivalent radius is under this fraction of
// the local vessel radius is a hole, larger ones are openings), then what
// the analysis repaired: a summary line (places re-surfaced, ends trimmed,
// fins, split edges and vertices, twists, specks, holes), the places
// re-surfaced where the surface crossed itself and the damaged ends
// trimmed (repair-places.js: listed in the page's words and lettered as
// their marks in the view), and the holes, listed (centre, radius against
// the vessel's, closed or left open) and marked on the surface. Changing a
// control analyzes the surface again.
import * as THREE from 'three';

import { disposeOverlay } from './overlay.js';
import { repairPlaces } from './repair-places.js';
import { length, point } from './units.js';

const $ = (id) => document.getElementById(id);
const MARK = 0xe07a00;
const MARK_HOVER = 0xd0104c;
// A hole's marker is at least this fraction of the bounding-box diagonal
// across, so a pin-hole is seen.
const MIN_MARK = 0.006;

const plural = (n, one, many = `${one}s`) => `${n} ${n === 1 ? one : many}`;

/** The analysis' repairs as one sentence, or '' when nothing was repaired
 * beyond welding. */
export function repairSummary(a) {
  const r = a.repairs ?? {};
  const closed = (a.holes ?? []).filter((h) => h.closed);
  const added = closed.reduce((n, h) => n + h.triangles_added, 0);
  const resurfaced = (r.crossings_resurfaced ?? []).filter((c) => c.resolved).length;
  const trimmed = (r.damaged_ends ?? []).filter((e) => e.trimmed).length;
  const parts = [
    [resurfaced, (n) => `${plural(n, 'place')} re-surfaced where the surface crossed itself`],
    [trimmed, (n) => `${plural(n, 'damaged end')} trimmed`],
    [r.fins_removed, (n) => `${plural(n, 'fin')} removed`],
    [r.nonmanifold_edges_split, (n) => `${plural(n, 'non-manifold edge')} split into sheets`],
    [r.nonmanifold_vertices_split, (n) => `${plural(n, 'non-manifold vertex', 'non-manifold vertices')} split`],
    [r.twisted_removed, (n) => `${plural(n, 'twisted triangle')} cut out`],
    [a.specks_removed, (n) => `${plural(n, 'speck')} removed`],
    [closed.length, (n) => `${plural(n, 'hole')} closed (${plural(added, 'triangle')} added)`],
  ]
    .filter(([n]) => n > 0)
    .map(([n, text]) => text(n));
  return parts.length ? `Repaired: ${parts.join(', ')}.` : '';
}

function element(tag, props = {}, testId = null) {
  const node = Object.assign(document.createElement(tag), props);
  if (testId) node.setAttribute('data-testid', testId);
  return node;
}

export class Repairs {
  /**
   * @param {object} hooks
   * @param {import('./viewer.js').Viewer} hooks.viewer
   * @param {import('./view-marks.js').ViewMarks} [hooks.marks] the repaired
   *   places' marks
   * @param {() => void} hooks.reanalyze analyzes the surface again with the
   *   step's options
   * @param {(message: string) => void} hooks.showError
   * @param {() => void} [hooks.showInput] shows the analyzed surface
   */
  constructor({ viewer, marks = null, reanalyze, showError, showInput = () => {} }) {
    Object.assign(this, { viewer, marks, reanalyze, showError, showInput });
    this.holes = [];
    this.places = [];
    this.group = null;
    this.visible = true;
    this.hovered = -1;
    $('repair').addEventListener('change', () => this.reanalyze());
    $('hole-fraction').addEventListener('change', () => {
      if (this._fraction() !== null) this.reanalyze();
    });
  }

  /** The hole fraction typed, or null (marked invalid) when not in [0, 1]. */
  _fraction() {
    const input = $('hole-fraction');
    const f = Number(input.value);
    const ok = input.value.trim() !== '' && f >= 0 && f <= 1;
    input.setAttribute('aria-invalid', String(!ok));
    if (!ok) this.showError('Holes: the size must be a fraction of the vessel radius from 0 to 1 (0: close no hole).');
    return ok ? f : null;
  }

  /** The analyze options of the controls: repair, holeFraction (only when
   * not the defaults). */
  prepOptions() {
    const prep = {};
    if ($('repair').value === 'off') prep.repair = 'off';
    const f = this._fraction();
    if (f !== null && f !== Number($('hole-fraction').defaultValue)) prep.holeFraction = f;
    return prep;
  }

  /** Sets the controls to the analyze options `prep`. */
  showPrep(prep) {
    $('repair').value = prep.repair ?? 'auto';
    $('hole-fraction').value = String(prep.holeFraction ?? $('hole-fraction').defaultValue);
    $('hole-fraction').setAttribute('aria-invalid', 'false');
  }

  /** Shows what `analysis` repaired and its holes. */
  show(analysis) {
    this.unit = analysis.units.unit;
    this.scale = analysis.bounding_box.diagonal;
    this.holes = analysis.holes ?? [];
    this.hovered = -1;
    $('repair-note').textContent = repairSummary(analysis);
    this._showPlaces(repairPlaces(analysis));
    const off = $('repair').value === 'off';
    $('holes-hint').textContent = off
      ? 'Repair is off: every boundary loop is an opening, none is closed.'
      : this.holes.length
        ? `${plural(this.holes.length, 'hole')} found (boundary loops under ${length($('hole-fraction').value)} of the vessel radius), marked in orange on the surface.`
        : 'No holes found.';
    const rows = this.holes.map((hole, i) => this._row(hole, i));
    $('holes').querySelector('tbody').replaceChildren(...rows);
    $('holes').hidden = rows.length === 0;
    this._draw();
  }

  /** Whether the analyzed surface is the one in the view (the markers show
   * only on it). */
  setVisible(on) {
    this.visible = on;
    this.marks?.show('repairs', on);
    this._draw();
  }

  /** Lists the repaired places (lettered as their marks) and marks them. */
  _showPlaces(places) {
    this.places = places;
    const rows = places.map((p) => {
      const li = element('li', {}, 'repair-place');
      li.dataset.id = p.id;
      li.dataset.kind = p.kind;
      const id = element('span', { className: 'repair-id', textContent: p.id });
      id.setAttribute('aria-hidden', 'true');
      const show = element('button', { type: 'button', className: 'repair-show', textContent: 'Show' }, 'repair-show');
      show.setAttribute('aria-label', `Show repair ${p.id} in the view`);
      show.addEventListener('click', () => {
        this.showInput();
        this.viewer.focusOn(p.point, p.radius);
      });
      li.append(id, element('span', { textContent: p.text }), show);
      li.addEventListener('pointerenter', () => this.marks?.activeRepair(p.id));
      li.addEventListener('pointerleave', () => this.marks?.activeRepair(null));
      return li;
    });
    $('repair-places').replaceChildren(...rows);
    $('repair-places').hidden = rows.length === 0;
    this.marks?.setRepairs(places, {
      onHover: (id) => {
        for (const li of rows) li.classList.toggle('active', li.dataset.id === id);
      },
    });
  }

  setBusy(on) {
    $('repair').disabled = on;
    $('hole-fraction').disabled = on;
  }

  _row(hole, i) {
    const tr = element('tr', {}, 'hole-row');
    tr.dataset.state = hole.closed ? 'closed' : 'open';
    const state = hole.closed ? `closed, ${plural(hole.triangles_added, 'triangle')}` : 'left open';
    const cells = [
      String(i + 1),
      point(hole.centroid, this.scale),
      `${length(hole.radius)} (${length(hole.radius / hole.vessel_radius)} R)`,
      state,
    ];
    for (const text of cells) tr.append(element('td', { textContent: text }));
    tr.addEventListener('pointerenter', () => this._hover(i));
    tr.addEventListener('pointerleave', () => this._hover(-1));
    return tr;
  }

  _hover(i) {
    this.hovered = i;
    this._draw();
  }

  _clear() {
    this.group = disposeOverlay(this.viewer, this.group);
  }

  /** A translucent ball on each hole, 1.5 times its radius (at least
   * MIN_MARK of the model), drawn over the surface. */
  _draw() {
    this._clear();
    if (!this.visible || !this.holes.length) return;
    this.group = new THREE.Group();
    this.holes.forEach((hole, i) => {
      const r = Math.max(1.5 * hole.radius, MIN_MARK * this.scale);
      const ball = new THREE.Mesh(
        new THREE.SphereGeometry(r, 16, 12),
        new THREE.MeshBasicMaterial({
          color: i === this.hovered ? MARK_HOVER : MARK,
          transparent: true,
          opacity: i === this.hovered ? 0.8 : 0.5,
          depthTest: false,
        }),
      );
      ball.renderOrder = 3;
      ball.position.set(...hole.centroid);
      this.group.add(ball);
    });
    this.viewer.addOverlay(this.group);
  }
}
