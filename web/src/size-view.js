// The size field before meshing, in the Mesh step: "Colour by" the local
// vessel radius R or the edge length h the size options ask for (the core's
// sizeField(), through the worker), on the input surface, with a legend in
// the model's unit (min, round ticks, max). The colours follow the size
// options as they are edited (debounced). The radius also answers the
// measure tool's "radius at a point" (nearest vertex).
import { scalarColor, scalarGradientCss } from './colormap.js';
import { niceTicks, rampPosition, valueRange } from './scalar-legend.js';
import { length } from './units.js';

const $ = (id) => document.getElementById(id);
const DEBOUNCE_MS = 300;
const TITLES = { radius: 'Vessel radius R', size: 'Edge size h' };

/** The index of the vertex of `positions` (3 floats a vertex) nearest p. */
export function nearestVertex(positions, p) {
  let best = -1;
  let bestD = Infinity;
  for (let v = 0, i = 0; i < positions.length; v++, i += 3) {
    const d = (positions[i] - p[0]) ** 2 + (positions[i + 1] - p[1]) ** 2 + (positions[i + 2] - p[2]) ** 2;
    if (d < bestD) [best, bestD] = [v, d];
  }
  return best;
}

export class SizeView {
  /**
   * @param {object} hooks
   * @param {import('./viewer.js').Viewer} hooks.viewer
   * @param {(options: object) => Promise<object>} hooks.sizeField the
   *   worker's sizeField() on the current surface, or {ok: false, error}
   * @param {() => object} hooks.sizeOptions the panel's size options
   * @param {() => object|null} hooks.surface the analyzed surface (its
   *   identity changes with each analysis), null before one
   * @param {() => boolean} hooks.canColour whether the view shows it
   * @param {() => void} hooks.showInput shows it in the view
   */
  constructor({ viewer, sizeField, sizeOptions, surface, canColour, showInput }) {
    Object.assign(this, { viewer, sizeField, sizeOptions, surface, canColour, showInput });
    this.mode = 'none';
    this.field = null; // {surface, key, radius, size, unit} of the last answer
    this.seq = 0;
    this.timer = 0;
    $('size-legend').querySelector('.ramp').style.background = scalarGradientCss();
    $('colour-by').addEventListener('change', () => this.select($('colour-by').value));
  }

  /** Colours by 'none', 'radius' or 'size'. */
  select(mode) {
    this.mode = mode;
    $('colour-by').value = mode;
    if (mode !== 'none' && this.surface() && !this.canColour()) this.showInput(); // calls shown()
    this.update();
  }

  /** The size options changed: the colours follow, debounced. */
  optionsChanged() {
    clearTimeout(this.timer);
    if (this.mode === 'none') return;
    this.timer = setTimeout(() => this.update(), DEBOUNCE_MS);
  }

  /** The view shows another content (main.js show()): colours again when
   * it is the input surface, else only the γ legend applies. */
  shown() {
    this.update();
  }

  /** The answer for the current surface and options (asked when needed). */
  async _field() {
    const surface = this.surface();
    if (!surface) return null;
    const options = this.sizeOptions();
    const key = JSON.stringify(options);
    if (this.field?.surface === surface && this.field.key === key) {
      this.seq++; // an answer still on its way is older
      this._status('');
      return this.field;
    }
    const seq = ++this.seq;
    this._status('Computing the size field…');
    const result = await this.sizeField(options);
    if (seq !== this.seq || surface !== this.surface()) return null; // superseded
    if (!result.ok) {
      this._status(`No size field: ${result.error}`, true);
      return null;
    }
    this._status('');
    this.field = { surface, key, radius: result.radius, size: result.size, unit: result.unit };
    return this.field;
  }

  async update() {
    clearTimeout(this.timer);
    if (this.mode === 'none' || !this.surface()) {
      this._status('');
      this._legend(null);
      if (this.canColour()) this.viewer.setVertexColors(null);
      return;
    }
    if (!this.canColour()) {
      // The remeshed surface or the volume is shown: nothing to colour.
      this._legend(null);
      this._status('Drawn on the input surface: choose Show: Input surface.');
      return;
    }
    const field = await this._field();
    if (this.mode === 'none') return;
    if (!field || !this.canColour()) {
      this._legend(null);
      return;
    }
    const values = field[this.mode];
    const range = valueRange(values);
    if (!range) return;
    const colors = new Float32Array(3 * values.length);
    for (let v = 0; v < values.length; v++) scalarColor(rampPosition(values[v], ...range), colors, 3 * v);
    if (this.viewer.setVertexColors(colors)) this._legend({ range, unit: field.unit });
  }

  /**
   * The local vessel radius at the vertex of the analyzed surface nearest
   * `point`: {ok, radius, unit} (asked of the core once per surface).
   */
  async radiusAt(point) {
    const surface = this.surface();
    if (!surface) return { ok: false, error: 'no surface loaded' };
    let field = this.field?.surface === surface ? this.field : null;
    if (!field) {
      // R does not depend on the size options: the defaults, if the
      // panel's are unusable.
      const result = await this.sizeField({});
      if (!result.ok) return result;
      if (surface !== this.surface()) return { ok: false, error: 'the surface changed' };
      field = { surface, key: '', radius: result.radius, size: result.size, unit: result.unit };
      if (this.field?.surface !== surface) this.field = field;
    }
    const v = nearestVertex(surface.positions, point);
    return { ok: v >= 0, radius: field.radius[v], unit: field.unit, vertex: v };
  }

  _status(text, error = false) {
    $('colour-status').textContent = text;
    $('colour-status').classList.toggle('error-text', error);
  }

  /** The legend of `range` ([min, max]) in `unit`, or none (the γ legend
   * back when the input surface shows quality). */
  _legend(shown) {
    const legend = $('size-legend');
    legend.hidden = !shown;
    // On the input surface one legend applies: this one, or quality's. On
    // the other contents main.js decides.
    if (shown) $('legend').hidden = true;
    else if (this.canColour() && this.surface()) $('legend').hidden = false;
    if (!shown) return;
    const [lo, hi] = shown.range;
    legend.dataset.mode = this.mode;
    legend.dataset.min = String(lo);
    legend.dataset.max = String(hi);
    legend.querySelector('.legend-title').textContent = `${TITLES[this.mode]} (${shown.unit})`;
    legend.querySelector('[data-end=min]').textContent = length(lo);
    legend.querySelector('[data-end=max]').textContent = length(hi);
    const ticks = niceTicks(lo, hi, 4).filter((t) => rampPosition(t, lo, hi) > 0.12 && rampPosition(t, lo, hi) < 0.88);
    legend.dataset.ticks = ticks.join(' ');
    legend.querySelector('.ticks').replaceChildren(
      ...ticks.map((t) => {
        const span = document.createElement('span');
        span.textContent = length(t);
        span.style.left = `${100 * rampPosition(t, lo, hi)}%`;
        return span;
      }),
    );
    legend.setAttribute(
      'aria-label',
      `${TITLES[this.mode]} from ${length(lo)} to ${length(hi)} ${shown.unit}, dark (small) to light (large)`,
    );
  }
}
