// Measurements on the surface shown (input or remeshed), in any step:
// "Measure", then a click on the surface gives the local vessel radius there
// (the size field's R at the nearest vertex of the analyzed surface), a
// second click the distance between the two points, drawn as a line; a third
// click starts a new measurement. From the keyboard: orbit the view with
// the arrow keys and press "Measure at centre" (the view's). Escape stops.
import * as THREE from 'three';

import { disposeOverlay } from './overlay.js';
import { listenSurfaceClicks, showClickMode, viewCentre } from './surface-clicks.js';
import { length, point } from './units.js';

const $ = (id) => document.getElementById(id);
const COLOR = 0xd0104c;

/** The Euclidean distance between two points [x, y, z]. */
export const distance = (a, b) => Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);

export class Measure {
  /**
   * @param {object} hooks
   * @param {import('./viewer.js').Viewer} hooks.viewer
   * @param {(point: number[]) => Promise<object>} hooks.radiusAt {ok,
   *   radius, unit} at the analyzed surface's vertex nearest a point
   * @param {() => {unit: string, scale: number}} hooks.model the model's
   *   unit and size (bounding-box diagonal), or null before one is loaded
   * @param {() => boolean} hooks.canPick whether a surface is shown
   * @param {() => void} hooks.showSurface shows one (else nothing to click)
   * @param {() => void} hooks.onStart the other click modes must stop
   */
  constructor({ viewer, radiusAt, model, canPick, showSurface, onStart = () => {} }) {
    Object.assign(this, { viewer, radiusAt, model, canPick, showSurface, onStart });
    this.active = false;
    this.points = [];
    this.radii = [];
    this.group = null;
    this.seq = 0;
    $('measure').addEventListener('click', () => this.setActive(!this.active));
    $('measure-center').addEventListener('click', () => this._pickAt(...viewCentre(this.viewer)));
    listenSurfaceClicks($('viewer'), {
      active: () => this.active,
      onClick: (x, y) => this._pickAt(x, y),
      onHover: (x, y) => {
        const at = this.viewer.pick(x, y);
        const { unit, scale } = this.model() ?? { unit: '', scale: 0 };
        $('pick-info').hidden = false;
        $('pick-info').textContent = at ? `Click to measure at ${point(at, scale)} ${unit}` : 'Not on the surface';
      },
      onEscape: () => this.setActive(false),
    });
  }

  /** Turns measuring on (the points start again) or off (the drawing and
   * the result go). */
  setActive(on) {
    this.active = on && Boolean(this.model());
    this.points = [];
    this.radii = [];
    this.seq++;
    if (this.active) {
      this.onStart();
      if (!this.canPick()) this.showSurface();
    }
    showClickMode(this.active, {
      button: 'measure',
      centre: 'measure-center',
      onLabel: 'Stop measuring (Esc)',
      offLabel: 'Measure',
      hint: 'Click a point: its vessel radius; a second point: the distance',
    });
    this._show();
  }

  /** Stops measuring (another click mode starts, a new file: then the
   * button is usable). */
  stop() {
    $('measure').disabled = !this.model();
    if (this.active || this.points.length) this.setActive(false);
  }

  async _pickAt(x, y) {
    const at = this.viewer.pick(x, y);
    if (!at) {
      $('pick-info').hidden = false;
      $('pick-info').textContent = 'Not on the surface: click on the surface (or orbit it under the view’s centre)';
      return;
    }
    if (this.points.length === 2) {
      this.points = [];
      this.radii = [];
    }
    const i = this.points.length;
    this.points.push(at);
    this.radii.push(null);
    this._show();
    const seq = this.seq;
    const r = await this.radiusAt(at);
    if (seq !== this.seq || this.points[i] !== at) return; // superseded
    this.radii[i] = r.ok ? r.radius : r.error;
    this._show();
  }

  /** The result's text (and its numbers as data attributes) and drawing. */
  _show() {
    const info = $('measure-info');
    const { unit, scale } = this.model() ?? { unit: '', scale: 0 };
    const [a, b] = this.points;
    const radius = (k) => {
      const r = this.radii[k];
      if (r === null) return 'R …';
      return typeof r === 'number' ? `R ${length(r)} ${unit}` : `no radius (${r})`;
    };
    info.hidden = !a;
    info.dataset.points = JSON.stringify(this.points);
    info.dataset.radius = typeof this.radii[0] === 'number' ? String(this.radii[0]) : '';
    info.dataset.distance = b ? String(distance(a, b)) : '';
    if (b) {
      info.textContent =
        `Distance ${length(distance(a, b))} ${unit} from ${point(a, scale)} to ${point(b, scale)}; ` +
        `vessel radius ${radius(0)} at the first, ${radius(1)} at the second.`;
    } else if (a) {
      info.textContent = `Point ${point(a, scale)} ${unit}: vessel radius ${radius(0)}. Click a second point for a distance.`;
    } else {
      info.textContent = '';
    }
    this._draw();
  }

  _draw() {
    this.group = disposeOverlay(this.viewer, this.group);
    if (!this.points.length) return;
    const { scale } = this.model() ?? { scale: 1 };
    this.group = new THREE.Group();
    const material = () => new THREE.MeshBasicMaterial({ color: COLOR, depthTest: false });
    for (const p of this.points) {
      const dot = new THREE.Mesh(new THREE.SphereGeometry(0.006 * scale, 12, 8), material());
      dot.position.set(...p);
      dot.renderOrder = 3;
      this.group.add(dot);
    }
    if (this.points.length === 2) {
      const geometry = new THREE.BufferGeometry().setFromPoints(this.points.map((p) => new THREE.Vector3(...p)));
      const line = new THREE.Line(geometry, new THREE.LineBasicMaterial({ color: COLOR, depthTest: false }));
      line.renderOrder = 3;
      this.group.add(line);
    }
    this.viewer.addOverlay(this.group);
  }
}
