// The openings table: one row per opening of the analysis (largest first,
// numbered as the API's `inlet` and `names` number them) with the inlet
// choice, the group name its cap gets (prefilled with the core's default
// name; a name the user types is checked by the core as they type), where
// the opening comes from (an open end of the file, or a cap the core
// removed, or a cut), its size, its flow extension (in local radii; the
// "all openings" field sets every row), and after meshing the name of the
// cap that covers it. Each row has its colour's swatch (the colour of its
// group: its label in the view and its cap in the mesh). Hovering a row,
// or focusing it or its name, highlights the rim in the view; a click on
// the opening's label in the view selects the row (select()).
import { groupColors } from './groups.js';
import { point, withUnit } from './units.js';
import { cssColor } from './view-marks.js';
import { inPageWords } from './words.js';

const CHECK_DELAY_MS = 250;

/** 'open end', 'cut', 'cap', 'cap, ModelFaceID 3'. */
function sourceText(opening, labelArray) {
  if (opening.source === 'clip') return 'cut';
  if (opening.source !== 'cap') return 'open end';
  return opening.label >= 0 && labelArray ? `cap, ${labelArray} ${opening.label}` : 'cap';
}

function element(tag, props = {}, testId = null) {
  const node = Object.assign(document.createElement(tag), props);
  if (testId) node.setAttribute('data-testid', testId);
  return node;
}

export class OpeningsTable {
  /**
   * @param {HTMLOListElement} list
   * @param {object} hooks
   * @param {(options: {names: object, inlet?: number}) => Promise<object>} hooks.openingNames the
   *   core's names of the openings with these options: {ok, names} or its refusal {ok: false, error, option}
   * @param {(loop: number[] | null, k: number | null) => void} hooks.onHover the rim to
   *   highlight (of opening k), or null
   * @param {HTMLInputElement} hooks.allExtensions the flow extension of every opening
   * @param {(openings: {k, name, point, color}[]) => void} [hooks.onColors] the
   *   openings' names and colours changed (the labels in the view follow)
   */
  constructor(list, { openingNames, onHover, allExtensions, onColors = () => {} }) {
    this.onColors = onColors;
    this.list = list;
    this.allExtensions = allExtensions;
    allExtensions.addEventListener('input', () => {
      for (const row of this.rows) row.extension.value = allExtensions.value;
      this.extensionProblem();
    });
    this.openingNames = openingNames;
    this.onHover = onHover;
    this.rows = [];
    this.seq = 0; // the newest check; older ones are dropped
    this.timer = null;
    this.checking = Promise.resolve({ names: {}, problem: null });
  }

  /**
   * One row per opening (lengths in `unit`, coordinates near 0 at `scale`
   * shown as 0, cap labels from the face array `labelArray`); `edits` (name
   * per row index) restores names the user typed (when the openings are the
   * same ones again). Checks the names.
   */
  show(openings, { unit, labelArray, scale }, edits = []) {
    this.seq++;
    this.rows = openings.map((o, i) => this._row(o, i, { unit, labelArray, scale }));
    this.list.replaceChildren(...this.rows.map((r) => r.li));
    this.rows.forEach((row, i) => {
      if (edits[i]) [row.input.value, row.edited] = [edits[i], true];
    });
    this._colour();
    if (this.rows.length) this.check();
  }

  /** The group name each row's cap gets: the typed one, else the default. */
  _names() {
    return this.rows.map((r) => r.input.value.trim() || r.input.placeholder || `opening_${r.k}`);
  }

  /** Gives each row's swatch its group's colour (as the mesh's groups get
   * them: groups.js) and tells the view's labels. */
  _colour() {
    const names = this._names();
    const colors = groupColors(['wall', ...names]).slice(1);
    this.rows.forEach((row, i) => {
      row.swatch.style.background = cssColor(colors[i]);
      row.swatch.title = `Colour of ${names[i]}`;
    });
    this.onColors(this.labels());
  }

  /** The openings as the view labels them: {k, name, point, color}; the
   * point is the cap's centroid after meshing (caps moved by a flow
   * extension), else the opening's. */
  labels() {
    const names = this._names();
    const colors = groupColors(['wall', ...names]).slice(1);
    return this.rows.map((row, i) => ({
      k: row.k,
      name: names[i],
      point: row.capCentroid ?? row.opening.centroid,
      color: colors[i],
    }));
  }

  /** Highlights opening k's row and rim (null: none), as hovering it does. */
  highlight(k) {
    for (const row of this.rows) row.li.classList.toggle('active', row.k === k);
    const row = this.rows[k - 1];
    this.onHover(row ? row.opening.vertices : null, row ? k : null);
  }

  /** Selects opening k: its row scrolled into sight and focused (its rim
   * highlighted). */
  select(k) {
    const row = this.rows[k - 1];
    if (!row) return;
    row.li.scrollIntoView({ block: 'nearest', behavior: 'instant' });
    row.li.focus({ preventScroll: true });
  }

  _row(o, i, { unit, labelArray, scale }) {
    const k = i + 1;
    const title = `Opening ${k}: ${o.vertices.length} rim vertices`;
    const li = element('li', { tabIndex: 0, title }, 'opening-item');
    li.dataset.source = o.source;
    const radio = element('input', { type: 'radio', name: 'inlet', value: String(k), checked: i === 0 }, 'inlet-choice');
    const choice = element('label', { className: 'inlet-choice', title: 'Cap this opening as the inlet' });
    choice.append(radio, ' inlet');
    radio.setAttribute('aria-label', `Opening ${k} is the inlet`);
    const input = element('input', { type: 'text', className: 'opening-name', spellcheck: false }, 'opening-name');
    // The analysis' default name until the core has checked the table.
    Object.assign(input, { autocomplete: 'off', value: o.name ?? '', placeholder: o.name ?? '' });
    input.setAttribute('aria-label', `Group name of opening ${k}`);
    input.setAttribute('aria-describedby', `opening-name-error-${k}`);
    const cap = element('span', { className: 'cap-name', title: 'Its cap in the mesh' }, 'opening-cap');
    const swatch = element('span', { className: 'swatch' }, 'opening-swatch');
    swatch.setAttribute('aria-hidden', 'true');
    const extension = element('input', { type: 'number', min: '0', max: '100', step: 'any' }, 'opening-extension');
    extension.value = this.allExtensions.value;
    extension.setAttribute('aria-label', `Flow extension of opening ${k}, in local radii (0: none)`);
    extension.addEventListener('input', () => extension.setAttribute('aria-invalid', 'false'));
    const flowLabel = element('label', { title: 'Flow extension, in local radii (0: none)' });
    flowLabel.append('flow extension ', extension, ' R');
    const shift = element('span', { className: 'cap-shift' }, 'opening-shift');
    const flow = element('div', { className: 'flow-ext' });
    flow.append(flowLabel, shift);
    const source = element('span', { className: 'source', textContent: sourceText(o, labelArray) }, 'opening-source');
    const size = `perimeter ${withUnit(o.perimeter, unit)}, radius ${withUnit(o.radius, unit)}`;
    const at = `at ${point(o.centroid, scale)} ${unit}`;
    const info = element('div', { className: 'opening-info' });
    info.append(source, `: ${size}, ${at}`);
    const error = element('div', { className: 'name-error', id: `opening-name-error-${k}` }, 'opening-name-error');
    const head = element('div', { className: 'opening-head' });
    const number = element('span', { className: 'opening-number', textContent: String(k) });
    number.setAttribute('aria-hidden', 'true');
    head.append(swatch, number, choice, input, cap);
    li.append(head, info, flow, error);
    const row = { k, li, input, radio, error, cap, swatch, extension, shift, opening: o, edited: false };
    this._listen(row, radio);
    return row;
  }

  _listen(row, radio) {
    const { li, input } = row;
    const on = () => {
      li.classList.add('active');
      this.onHover(row.opening.vertices, row.k);
    };
    const off = () => {
      li.classList.remove('active');
      this.onHover(null, null);
    };
    li.addEventListener('mouseenter', on);
    li.addEventListener('mouseleave', () => {
      if (!li.contains(document.activeElement)) off(); // still highlighted while its name is edited
    });
    li.addEventListener('focusin', on);
    li.addEventListener('focusout', (e) => {
      if (!li.contains(e.relatedTarget)) off();
    });
    input.addEventListener('input', () => {
      row.edited = input.value.trim() !== '';
      this._schedule();
    });
    input.addEventListener('blur', () => this.check()); // a cleared name gets its default back
    input.addEventListener('keydown', (e) => {
      if (e.key === 'Enter') this.check();
    });
    radio.addEventListener('change', () => this.check()); // the default names follow the inlet
  }

  _schedule() {
    clearTimeout(this.timer);
    this.timer = setTimeout(() => this.check(), CHECK_DELAY_MS);
  }

  /** The chosen inlet (1-based into analysis.openings), or undefined. */
  chosenInlet() {
    const radio = this.list.querySelector('input[name=inlet]:checked');
    return radio ? Number(radio.value) : undefined;
  }

  /** The flow extensions typed: {K: L} of the openings with L > 0. */
  flowExtensions() {
    const out = {};
    for (const row of this.rows) {
      const value = Number(row.extension.value);
      if (value > 0) out[row.k] = value;
    }
    return out;
  }

  /** Why a flow extension typed is unusable (rows marked), or null. */
  extensionProblem() {
    const ok = (input) => {
      const v = input.value.trim();
      return !input.validity.badInput && (v === '' || (Number(v) >= 0 && Number(v) <= 100));
    };
    let problem = null;
    for (const input of [this.allExtensions, ...this.rows.map((r) => r.extension)]) {
      input.setAttribute('aria-invalid', String(!ok(input)));
      problem ??= ok(input) ? null : input.getAttribute('aria-label') ?? 'Flow extension, all openings';
    }
    return problem && `${problem}: a length from 0 to 100 local radii.`;
  }

  /** The choices of the table: the typed names (edits()), the inlet, the
   * flow extensions (all openings' field and each row's), as typed. */
  state() {
    return {
      names: this.edits(),
      inlet: this.chosenInlet() ?? 1,
      flowAll: this.allExtensions.value,
      extensions: this.rows.map((r) => r.extension.value),
    };
  }

  /** Sets the table's choices to a state() of the same openings; the names
   * are checked again (a row without a typed name gets its default). */
  setState({ names = [], inlet = 1, flowAll = '0', extensions = [] }) {
    this.allExtensions.value = flowAll;
    for (const [i, row] of this.rows.entries()) {
      row.edited = Boolean(names[i]);
      if (row.edited) row.input.value = names[i];
      row.radio.checked = row.k === inlet;
      row.extension.value = extensions[i] ?? flowAll;
    }
    this.extensionProblem();
    if (this.rows.length) this.check();
  }

  /** The names the user typed, by row index ('' where none). */
  edits() {
    return this.rows.map((r) => (r.edited ? r.input.value.trim() : ''));
  }

  /**
   * Checks the typed names now (the core's openingNames): each typed name
   * is tried with the accepted ones before it, so a refusal lands on the row
   * that causes it; rows left to the default show the core's default name.
   * Resolves { names: {K: name} of the accepted typed names, problem: {k,
   * message} of the first refused row, or null }.
   */
  check() {
    clearTimeout(this.timer);
    this.checking = this._check(++this.seq);
    return this.checking;
  }

  async _check(seq) {
    const inlet = this.chosenInlet();
    const ask = (names) => this.openingNames({ names, ...(inlet !== undefined && { inlet }) });
    let accepted = {};
    const refusals = new Map();
    for (const row of this.rows.filter((r) => r.edited)) {
      const trial = { ...accepted, [row.k]: row.input.value.trim() };
      const result = await ask(trial);
      if (seq !== this.seq) return this.checking;
      if (result.ok) accepted = trial;
      else if (result.option === 'names') refusals.set(row, result.error);
      else return { names: trial, problem: null }; // not checkable now: mesh() checks them
    }
    const all = await ask(accepted);
    if (seq !== this.seq) return this.checking;
    this._mark(refusals, all.ok ? all.names : null);
    const [first] = refusals;
    return { names: accepted, problem: first ? { k: first[0].k, message: inPageWords(first[1]) } : null };
  }

  /** Marks refused rows; gives the others their default name (not the one being typed in). */
  _mark(refusals, names) {
    for (const row of this.rows) {
      const message = inPageWords(refusals.get(row) ?? '');
      row.input.setAttribute('aria-invalid', String(Boolean(message)));
      row.error.textContent = message;
      if (!names || row.edited) continue;
      row.input.placeholder = names[row.k - 1];
      if (document.activeElement !== row.input) row.input.value = names[row.k - 1];
    }
    this._colour();
  }

  /** Moves the focus to opening k's name (e.g. to correct it). */
  focusName(k) {
    this.rows[k - 1]?.input.focus();
  }

  /**
   * Names each opening after the cap of the mesh that covers it (the cap of
   * its name, else the nearest cap centroid): data-cap and a label "→
   * inlet"; data-cap-shift is how far the cap lies from the opening (a flow
   * extension moved it), said when more than a tenth of the opening's
   * radius. No caps: names cleared.
   * @param {{name: string, centroid: number[]}[]} caps report.output.caps
   * @param {string} unit
   */
  showCaps(caps = [], unit = '') {
    for (const row of this.rows) {
      const { li, cap: label, opening, input, shift: said } = row;
      const c = opening.centroid;
      const distance = (cap) => Math.hypot(...cap.centroid.map((x, k) => x - c[k]));
      let best = caps.find((cap) => cap.name === input.value.trim()) ?? null;
      if (!best) {
        for (const cap of caps) if (!best || distance(cap) < distance(best)) best = cap;
      }
      const name = best ? best.name : '';
      const shift = best ? distance(best) : 0;
      li.dataset.cap = name;
      li.dataset.capShift = best ? String(shift) : '';
      row.capCentroid = best?.centroid ?? null;
      label.textContent = name ? `→ ${name}` : '';
      said.textContent = shift > 0.1 * opening.radius ? `: its cap ${withUnit(shift, unit)} out` : '';
    }
    this.onColors(this.labels());
  }
}
