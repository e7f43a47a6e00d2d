// Local refinement in the Mesh step: spheres inside which the mesh is finer
// (the core's `refine` option, X,Y,Z,R,H a sphere: edges of at most H
// within R of the centre, graded out of it, on the wall and in the volume).
// "Add a refinement", then a click on the surface, places one there; its
// radius and size are edited in its row, and it is drawn on the surface as a
// translucent ball. The spheres belong to the file: a new file clears them.
import * as THREE from 'three';

import { disposeOverlay } from './overlay.js';
import { listenSurfaceClicks, showClickMode, viewCentre } from './surface-clicks.js';
import { point } from './units.js';

const $ = (id) => document.getElementById(id);
const COLOR = 0x2a9d4b;

function element(tag, props = {}, testId = null) {
  const node = Object.assign(document.createElement(tag), props);
  if (testId) node.setAttribute('data-testid', testId);
  return node;
}

export class Refinements {
  /**
   * @param {object} hooks
   * @param {import('./viewer.js').Viewer} hooks.viewer
   * @param {() => boolean} hooks.canPick whether the view shows a surface
   *   that can be clicked (else the surface is shown first by showSurface)
   * @param {() => void} hooks.showSurface shows the surface in the view
   * @param {() => void} hooks.onAdding another click mode must stop
   * @param {() => void} hooks.onChange the spheres changed (added, edited, removed)
   */
  constructor({ viewer, canPick, showSurface, onAdding = () => {}, onChange = () => {} }) {
    Object.assign(this, { viewer, canPick, showSurface, onAdding, onChange });
    this.spheres = []; // {center: [x, y, z], radius, size}
    this.adding = false;
    this.visible = true;
    this.busy = false;
    this.group = null;
    this.unit = 'mm';
    this.scale = 1;
    // By keyboard: the view turned (arrow keys) to have the spot in its centre.
    $('refine-center').addEventListener('click', () => this._addAt(...viewCentre(this.viewer)));
    $('add-refine').addEventListener('click', () => this.setAdding(!this.adding));
    listenSurfaceClicks($('viewer'), {
      active: () => this.adding,
      onClick: (x, y) => this._addAt(x, y),
      onHover: (x, y) => {
        const at = this.viewer.pick(x, y);
        $('pick-info').hidden = false;
        $('pick-info').textContent = at ? `Click to refine around ${point(at, this.scale)} ${this.unit}` : 'Not on the surface';
      },
      onEscape: () => this.setAdding(false),
    });
  }

  /** A new file: no spheres; lengths in `unit`, `scale` the model's size. */
  reset({ unit, scale }) {
    Object.assign(this, { unit, scale, spheres: [] });
    this.setAdding(false);
    this._render();
  }

  /** The option's value: one [x, y, z, R, H] a sphere (empty: none). */
  options() {
    return this.spheres.map((s) => [...s.center, s.radius, s.size]);
  }

  /** Why a sphere's radius or size is unusable (the field is marked), or null. */
  problem() {
    const rows = $('refinements').querySelectorAll('tbody tr');
    for (const [i, s] of this.spheres.entries()) {
      for (const key of ['radius', 'size']) {
        const ok = Number.isFinite(s[key]) && s[key] > 0;
        rows[i]?.querySelector(`[data-testid=refine-${key}]`)?.setAttribute('aria-invalid', String(!ok));
        if (!ok) return `Local refinement ${i + 1}: the ${key} must be a length > 0 in ${this.unit}.`;
      }
    }
    return null;
  }

  setBusy(on) {
    this.busy = on;
    if (on) this.setAdding(false);
    $('add-refine').disabled = on;
    for (const input of $('refinements').querySelectorAll('input, button')) input.disabled = on;
  }

  /** Whether the spheres are drawn (the surfaces are shown, not the volume). */
  setVisible(on) {
    this.visible = on;
    this._draw();
  }

  /** Turns "click on the surface to add a refinement" on or off. */
  setAdding(on) {
    this.adding = on && !this.busy;
    if (this.adding) {
      this.onAdding();
      if (!this.canPick()) this.showSurface();
    }
    showClickMode(this.adding, {
      button: 'add-refine',
      centre: 'refine-center',
      onLabel: 'Click on the surface… (Esc: stop)',
      offLabel: 'Add a refinement',
      hint: 'Click on the surface where the mesh should be finer',
    });
  }

  _addAt(x, y) {
    const at = this.viewer.pick(x, y);
    if (!at) {
      $('pick-info').hidden = false;
      $('pick-info').textContent = 'No surface there: turn the view (arrow keys in the view) to bring the spot to its centre, or click on it';
      return;
    }
    // A start the user then edits: a ball 1/20 of the model across, edges
    // a fifth of its radius.
    const radius = Number((0.05 * this.scale).toPrecision(2));
    this.spheres.push({ center: at, radius, size: Number((radius / 5).toPrecision(2)) });
    this.setAdding(false);
    this._render();
    $('refinements').querySelector('tbody tr:last-child [data-testid=refine-radius]')?.focus();
  }

  _remove(i) {
    this.spheres.splice(i, 1);
    this._render();
    const buttons = $('refinements').querySelectorAll('button');
    (buttons[Math.min(i, buttons.length - 1)] ?? $('add-refine')).focus();
  }

  _render() {
    const rows = this.spheres.map((s, i) => this._row(s, i));
    $('refinements').querySelector('tbody').replaceChildren(...rows);
    $('refinements').hidden = rows.length === 0;
    this.onChange();
    $('refine-hint').textContent = rows.length
      ? 'Within each radius the edges are at most the size, growing smoothly outside.'
      : 'None: add one and click on the surface where the mesh should be finer (an aneurysm neck, a stenosis).';
    this._draw();
  }

  _row(s, i) {
    const k = i + 1;
    const tr = element('tr', {}, 'refine-row');
    const number = (key, label) => {
      const input = element('input', { type: 'number', min: '0', step: 'any', value: String(s[key]) }, `refine-${key}`);
      input.setAttribute('aria-label', `${label} of refinement ${k} (${this.unit})`);
      input.disabled = this.busy;
      input.addEventListener('input', () => {
        s[key] = input.value.trim() === '' ? NaN : Number(input.value);
        input.setAttribute('aria-invalid', 'false');
        this._draw();
        this.onChange();
      });
      return input;
    };
    const remove = element('button', { type: 'button', textContent: 'Remove' }, 'refine-remove');
    remove.setAttribute('aria-label', `Remove refinement ${k}`);
    remove.disabled = this.busy;
    remove.addEventListener('click', () => this._remove(i));
    for (const content of [
      element('span', { textContent: String(k) }),
      element('span', { textContent: point(s.center, this.scale) }),
      number('radius', 'Radius'),
      number('size', 'Size'),
      remove,
    ]) {
      const td = document.createElement('td');
      td.append(content);
      tr.append(td);
    }
    return tr;
  }

  _clear() {
    this.group = disposeOverlay(this.viewer, this.group);
  }

  _draw() {
    this._clear();
    const shown = this.spheres.filter((s) => s.radius > 0 && Number.isFinite(s.radius));
    if (!this.visible || !shown.length) return;
    this.group = new THREE.Group();
    for (const s of shown) {
      const ball = new THREE.Mesh(
        new THREE.SphereGeometry(s.radius, 24, 16),
        new THREE.MeshBasicMaterial({ color: COLOR, transparent: true, opacity: 0.25, depthWrite: false }),
      );
      ball.position.set(...s.center);
      this.group.add(ball);
    }
    this.viewer.addOverlay(this.group);
  }
}
