// "Mesh family" in the export area: a mesh-independence family (N meshes of
// the prepared surface, mesh k with every size divided by r^k) made by the
// worker's mesh() with the panel's mesh options plus {family, ratio,
// familyLayers}, downloaded as one zip (the meshes, family.csv and
// family.json) and tabled here: per mesh its cells, its h = (V/N)^(1/3),
// the ratio achieved to the previous one, its quality, its layers and its
// time. The fields' ranges and defaults are the core's option table's
// (index.html as built: option-controls.js; a family of one is no family:
// at least 2 meshes here).
import { baseName } from './files.js';

const count = (n) => n.toLocaleString('en');
const short = (x) => (Number.isFinite(x) ? String(Number(x.toPrecision(3))) : '–');
const sub = (text) => Object.assign(document.createElement('sub'), { textContent: text });

/** What the two boundary-layer choices are called here. */
const LAYER_WORDS = {
  refine: 'boundary layer refined with the family',
  fixed: 'one first-layer height (y+) in every mesh',
};

export class Family {
  /**
   * @param {object} hooks
   * @param {(extra: object) => Promise<object|null>} hooks.mesh meshes with the
   *   panel's options and `extra`; the result (shown), or null (the problem said)
   * @param {() => string} hooks.inputName the loaded file's name
   * @param {(name: string, bytes: Uint8Array, type: string) => void} hooks.download
   * @param {(message: string, next: string) => void} hooks.showError
   * @param {(name: string, family: object) => void} hooks.onDone
   * @param {(job: () => Promise<void>) => void} hooks.act runs a press, one at a time
   */
  constructor(hooks) {
    const $ = (id) => document.getElementById(id);
    this.hooks = hooks;
    this.members = $('family');
    this.ratio = $('ratio');
    this.layers = $('family-layers');
    this.table = $('family-table');
    for (const input of [this.members, this.ratio]) {
      input.addEventListener('input', () => input.setAttribute('aria-invalid', 'false'));
    }
    $('mesh-family').addEventListener('click', () => hooks.act(() => this.make()));
  }

  /** The family options of the fields, or null with the field marked and the problem said. */
  options() {
    const number = (input) => (input.value.trim() === '' || input.validity.badInput ? NaN : Number(input.value));
    const within = (input, x) => x >= Number(input.min) && x <= Number(input.max);
    const family = number(this.members);
    const ratio = number(this.ratio);
    const { members: m, ratio: r } = this;
    const bad = [
      [m, Number.isInteger(family) && within(m, family), `the number of meshes must be whole, ${m.min} to ${m.max}.`],
      [r, within(r, ratio), `the ratio must be from ${r.min} to ${r.max} (1.3 or more for a grid convergence index).`],
    ].filter(([input, ok]) => {
      input.setAttribute('aria-invalid', String(!ok));
      return !ok;
    });
    if (bad.length) {
      const next = 'Correct the field marked in red under Mesh family, then press Mesh family again.';
      this.hooks.showError(`Mesh family: ${bad[0][2]}`, next);
      bad[0][0].focus();
      return null;
    }
    return { family, ratio, familyLayers: this.layers.value };
  }

  /** Meshes the family, downloads its zip and tables it; the zip's name, or null. */
  async make() {
    const options = this.options();
    if (!options) return null;
    const result = await this.hooks.mesh(options);
    if (!result) return null;
    if (!result.family) {
      this.hooks.showError('Mesh family: the mesher made one mesh, not a family.', 'Press Mesh family again.');
      return null;
    }
    const name = `${baseName(this.hooks.inputName())}-mesh-family.zip`;
    this.hooks.download(name, result.file, 'application/zip');
    this.show(result.family, name);
    // The verdict of the first mesh took the focus: the table is what was asked for.
    this.table.closest('[data-family-box]').focus();
    this.hooks.onDone(name, result.family);
    return name;
  }

  /** Tables a family (the result's `family`), its zip named `name`. */
  show(family, name) {
    const unit = family.unit ? ` (${family.unit})` : '';
    // A short caption (it scrolls with a wide table on a phone); the rest under it.
    this.table.caption.textContent = `Mesh family: ${family.members} meshes, ratio ${family.ratio}`;
    document.getElementById('family-note').textContent =
      `Mesh 0 is the mesh as asked (shown in the view), mesh k has every size divided by ${family.ratio}^k; ` +
      `${LAYER_WORDS[family.layers] ?? family.layers}. Ratio: h of the mesh before over h, ` +
      `h = (V/N)^(1/3) of the lumen's volume V and its N cells; γt of all tetrahedra. Downloaded as ${name}.`;
    // A row per quantity, a column per mesh: narrow enough for the panel
    // (a row per mesh would need 8 columns).
    const corner = document.createElement('td');
    const head = document.createElement('tr');
    head.append(
      corner,
      ...family.rows.map((row) => {
        const th = document.createElement('th');
        th.scope = 'col';
        th.dataset.member = String(row.member);
        th.textContent = `Mesh ${row.member}`;
        return th;
      }),
    );
    this.table.tHead.replaceChildren(head);
    const quantities = [
      ['cells', 'Cells', (row) => count(row.cells)],
      ['h', `h${unit}`, (row) => short(row.h)],
      ['ratio', 'Ratio achieved', (row, k) => (k === 0 || !(row.ratio > 0) ? '–' : row.ratio.toFixed(2))],
      ['gamma-min', ['γ', sub('t'), ' min'], (row) => row.gamma_t_min.toFixed(3)],
      ['gamma-mean', ['γ', sub('t'), ' mean'], (row) => row.gamma_t_mean.toFixed(3)],
      ['layers', 'Layers', (row) => String(row.layers)],
      ['first-layer', `First layer${unit}`, (row) => (row.layers > 0 ? short(row.first_layer_height) : '–')],
      ['seconds', 'Time (s)', (row) => row.seconds.toFixed(1)],
    ];
    const rows = quantities.map(([stat, label, text]) => {
      const line = document.createElement('tr');
      line.dataset.stat = stat;
      const th = document.createElement('th');
      th.scope = 'row';
      th.append(...[label].flat());
      line.append(
        th,
        ...family.rows.map((row, k) => {
          const td = document.createElement('td');
          td.dataset.member = String(row.member);
          td.textContent = text(row, k);
          return td;
        }),
      );
      return line;
    });
    this.table.tBodies[0].replaceChildren(...rows);
    for (const box of document.querySelectorAll('[data-family-box]')) box.hidden = false;
  }

  /** Hides the table (a new file, or a mesh that is no family). */
  clear() {
    for (const box of document.querySelectorAll('[data-family-box]')) box.hidden = true;
  }
}
