// The options panel (the form): its controls read into the API's options
// (the analyze options of the preparation, the mesh options, the size
// options of the size view), which fields apply (the boundary layer's by
// its mode and number of layers, the vessel wall's, none for a surface
// only; the size's label and a start value when its mode changes), and
// whether each value is valid, by the core's option table (the worker
// sends it when ready; the core checks again). The refinements
// (refine.js), the openings' names, inlet and flow extensions (openings.js)
// and the cuts (prepare.js) join the options here.
import { fromDisplay } from './option-controls.js';
import { withUnitGuess } from './units.js';

const $ = (id) => document.getElementById(id);

/** The number in a number input (NaN when blank or not a number). */
export function numberIn(id) {
  const input = $(id);
  const value = input.value.trim();
  return input.validity.badInput || value === '' ? NaN : Number(value);
}

/** The number in an option's input as the option's value (a percent
 * field's: the fraction; option-controls.js). */
function optionNumber(id) {
  return fromDisplay(numberIn(id), $(id).dataset.display);
}

/** Marks `input` valid or not; returns `message` when it is not. */
function check(input, ok, message) {
  input.setAttribute('aria-invalid', String(!ok));
  return ok ? null : message;
}

/** The fields of the boundary layer and the vessel wall. */
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

export class OptionsForm {
  /**
   * @param {object} hooks
   * @param {() => object[]|undefined} hooks.table the core's option table (once the worker is ready)
   * @param {() => object|null} hooks.current the loaded file ({prep, unitGuess, analysis}), or null
   * @param {() => string} hooks.unitName the unit lengths are given in
   * @param {(options: object) => Promise<object>} hooks.layerFractions the API's layerFractions()
   * @param {import('./prepare.js').Prepare} hooks.prepare
   * @param {import('./refine.js').Refinements} hooks.refinements
   * @param {import('./openings.js').OpeningsTable} hooks.openings
   */
  constructor(hooks) {
    this.hooks = hooks;
  }

  /** The option table's row of the option of the control with this id (data-option), once the table is there. */
  spec(id) {
    const js = $(id).dataset.option;
    return this.hooks.table()?.find((s) => s.js === js);
  }

  /**
   * Whether `x`, a number in the control with this id, is a valid value of
   * its option, by the core's option table (its range, exclusive bounds
   * and, for integers, wholeness), within the narrower range the page
   * needs (data-min, data-max). The table's checks pass before it has
   * arrived (the core checks again).
   */
  fits(id, x) {
    const { min, max, display } = $(id).dataset;
    if ((min !== undefined && !(x >= Number(min))) || (max !== undefined && !(x <= Number(max)))) return false;
    const spec = this.spec(id);
    if (!spec) return true;
    const value = fromDisplay(x, display);
    if (!Number.isFinite(value) || (spec.type === 'integer' && !Number.isInteger(value))) return false;
    if (spec.min !== undefined && (spec.minExclusive ? value <= spec.min : value < spec.min)) return false;
    if (spec.max !== undefined && (spec.maxExclusive ? value >= spec.max : value > spec.max)) return false;
    return true;
  }

  /** What a valid value of the option of the control with this id is, from the table. */
  needs(id) {
    return this.spec(id)?.needs ?? 'a valid value';
  }

  /** The analyze options chosen in the panel (units, caps, components,
   * smoothing, the cuts made). */
  prepOptions() {
    const prep = this.hooks.prepare.prepOptions();
    if ($('units').value) prep.units = $('units').value;
    if ($('keep-caps').checked) prep.keepCaps = true;
    if ($('largest-component-only').checked) prep.largestComponentOnly = true;
    return prep;
  }

  /** Sets the analyze options' controls to `prep`. */
  showPrep(prep) {
    $('units').value = prep.units ?? '';
    $('keep-caps').checked = Boolean(prep.keepCaps);
    $('largest-component-only').checked = Boolean(prep.largestComponentOnly);
    this.hooks.prepare.showPrep(prep);
  }

  /** The size options of the size view: the size and the usable refinements. */
  sizeOptions() {
    const refine = this.hooks.refinements.options().filter(([, , , r, h]) => r > 0 && h > 0);
    return { [$('size-mode').value]: numberIn('size-value'), ...(refine.length && { refine }) };
  }

  /** The size fields, for a remedy's words ({mode, value, core}). */
  sizeContext() {
    return { mode: $('size-mode').value, value: numberIn('size-value'), core: numberIn('core-size') };
  }

  /** Why the core size field is unusable, or null (blank is the default). */
  coreSizeProblem() {
    const input = $('core-size');
    const value = input.value.trim();
    const bad = input.validity.badInput || (value !== '' && !(Number(value) >= 0));
    return check(input, !bad, `Core size must be a length ≥ 0 in ${this.hooks.unitName()}, or blank for the default.`);
  }

  /** Why the largest volume change field (a percent) is unusable, or null. */
  volumeChangeProblem() {
    const input = $('max-volume-change');
    const x = numberIn('max-volume-change');
    const ok = x >= Number(input.min) && x <= Number(input.max);
    return check(input, ok, `Largest volume change must be a percentage from ${input.min} to ${input.max} (Advanced).`);
  }

  /** Why the boundary layer or vessel wall fields are unusable: every field
   * that applies is marked, the first problem returned (null when all are
   * fine). */
  layerProblems() {
    for (const id of LAYER_FIELDS) $(id).setAttribute('aria-invalid', 'false');
    if ($('surface-only').checked) return null; // no volume: the fields are unused
    const needs = (id) => this.needs(id);
    const unit = this.hooks.unitName();
    const layers = numberIn('layers') > 0;
    const mode = $('layer-mode').value;
    const wall = $('wall-on').checked;
    // [field, applies, message]
    const rules = [
      ['layers', true, `Boundary layer: the number of layers must be ${needs('layers')}.`],
      ['layer-thickness', layers && mode === 'thickness', `Boundary layer: the total thickness must be ${needs('layer-thickness')} (e.g. 0.2).`],
      ['first-layer', layers && mode === 'first', `Boundary layer: the first-layer height must be ${needs('first-layer')} in ${unit}.`],
      ...[
        ['first-layer-yplus', 'the target y+'],
        ['inlet-velocity', 'the inlet velocity'],
        ['density', 'the density'],
        ['viscosity', 'the viscosity'],
      ].map(([id, what]) => [id, layers && mode === 'yplus', `Boundary layer: ${what} must be ${needs(id)}.`]),
      ['growth', layers, `Boundary layer: the growth must be ${needs('growth')}.`],
      ['wall-thickness', wall, `Vessel wall: the thickness must be ${needs('wall-thickness')} (e.g. 0.1).`],
      [
        'wall-layers',
        wall,
        `Vessel wall: the number of layers must be a whole number from ${$('wall-layers').min} (with the wall on).`,
      ],
    ];
    const problems = rules
      .filter(([, applies]) => applies)
      .map(([id, , message]) => check($(id), this.fits(id, numberIn(id)), message));
    return problems.find(Boolean) ?? null;
  }

  /** The first problem of the panel's mesh options (its fields, the
   * refinements, the flow extensions), each field marked; null when none. */
  problem() {
    const { refinements, openings } = this.hooks;
    const problems = [this.coreSizeProblem(), this.volumeChangeProblem(), refinements.problem(), this.layerProblems(), openings.extensionProblem()];
    return problems.find(Boolean) ?? null;
  }

  /** The mesh options chosen in the panel with the opening `names` (without
   * progress and the file to write). */
  meshOptions(names) {
    const { refinements, openings } = this.hooks;
    const current = this.hooks.current();
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
    const volumeChange = optionNumber('max-volume-change');
    const byDefault = fromDisplay(Number($('max-volume-change').defaultValue), $('max-volume-change').dataset.display);
    if (volumeChange !== byDefault) options.maxVolumeChange = volumeChange;
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
        options.prisms = $('prisms').checked;
      }
      if ($('wall-on').checked) {
        options.wallThickness = numberIn('wall-thickness');
        options.wallLayers = numberIn('wall-layers');
      }
    }
    return options;
  }

  /** Enables the layer fields that apply (none with 0 layers or surface only). */
  syncLayerFields() {
    const none = numberIn('layers') === 0;
    const yplusIds = ['first-layer-yplus', 'inlet-velocity', 'density', 'viscosity'];
    for (const id of ['layer-mode', 'layer-thickness', 'first-layer', ...yplusIds, 'growth', 'tag-layer', 'prisms']) {
      $(id).disabled = none;
    }
    const mode = $('layer-mode').value;
    $('layer-thickness-field').hidden = mode !== 'thickness';
    $('first-layer-field').hidden = mode !== 'first';
    $('yplus-fields').hidden = mode !== 'yplus';
    $('wall-thickness').disabled = $('wall-layers').disabled = !$('wall-on').checked;
    $('layer-options').disabled = $('wall-options').disabled = $('surface-only').checked;
  }

  /** The unit of the current model on every length label of the panel. */
  showUnit(unit) {
    for (const label of document.querySelectorAll('[data-unit-label]')) label.textContent = unit;
    $('output-units').options[0].textContent = `same as input (${unit})`;
    this.showSizeLabel();
  }

  /** 'N', or 'h (mm)' for a uniform size. */
  showSizeLabel() {
    $('size-label').textContent = $('size-mode').value === 'size' ? `h (${this.hooks.unitName()})` : 'N';
  }

  /**
   * A first-layer height to start from: the first of the current number of
   * layers, growing by the current ratio (the core's layer fractions), that
   * add up to the current total thickness fraction (0.2 if unusable) of the
   * median opening's radius; '' without openings.
   */
  async suggestedFirstLayer() {
    const radii = (this.hooks.current()?.analysis.openings ?? []).map((o) => o.radius).sort((a, b) => a - b);
    if (!radii.length) return '';
    const f = numberIn('layer-thickness');
    const total = (this.fits('layer-thickness', f) ? f : 0.2) * radii[Math.floor(radii.length / 2)];
    const layers = this.fits('layers', numberIn('layers')) && numberIn('layers') >= 1 ? numberIn('layers') : 4;
    const growth = this.fits('growth', numberIn('growth')) ? numberIn('growth') : 1;
    const r = await this.hooks.layerFractions({ layers, growth });
    return r.ok ? String(Number((total * r.fractions[1]).toPrecision(2))) : '';
  }

  /** Follows the controls: the size's label and start value, the fields
   * that apply, a field's mark cleared as it is edited. */
  listen() {
    $('size-mode').addEventListener('change', (e) => {
      const uniform = e.target.value === 'size';
      this.showSizeLabel();
      // A sensible start: 2 pi R / 20 of the median opening, or a 50th of the box.
      const current = this.hooks.current();
      const radii = (current?.analysis.openings ?? []).map((o) => o.radius).sort((a, b) => a - b);
      const diag = current?.analysis.bounding_box.diagonal ?? 1;
      const h = radii.length ? (2 * Math.PI * radii[Math.floor(radii.length / 2)]) / 20 : diag / 50;
      $('size-value').value = uniform ? Number(h.toPrecision(2)) : 20;
    });
    for (const id of ['core-size', 'max-volume-change', ...LAYER_FIELDS]) {
      $(id).addEventListener('input', () => $(id).setAttribute('aria-invalid', 'false'));
    }
    $('layers').addEventListener('input', () => this.syncLayerFields());
    $('layer-mode').addEventListener('change', (e) => {
      if (e.target.value === 'first' && $('first-layer').value.trim() === '') {
        this.suggestedFirstLayer().then((h) => {
          if ($('first-layer').value.trim() === '') $('first-layer').value = h;
        });
      }
      this.syncLayerFields();
    });
    $('wall-on').addEventListener('change', () => this.syncLayerFields());
  }
}
