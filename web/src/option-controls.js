// The page's option controls and the core's option table
// (wasm/src/option-table.json, written by wasm/scripts/gen-types.mjs from
// the WebAssembly module). A control that sets exactly one option is marked
// in index.html with data-option="<the option's JS key>", and its id is the
// key in kebab-case (coreSize: core-size), which is also its key in a
// settings link. Its range and default are not written in index.html: the
// build (web/vite.config.js, its dev server too) fills them in from the
// table, so the controls show them before the wasm module is ready:
// min, max and value (step 1 for an integer) of a number input, checked of
// a checkbox, the selected choice of a select. A control may say where it
// differs, each checked (web/test/option-controls.test.js):
//   data-display="percent"  shows the value in percent (the option is the fraction)
//   data-min, data-max      a narrower range the page needs (within the table's)
//   data-start              the value it starts with where the table's default
//                           is none it can show: the option has no default (a
//                           page control turns it on: the wall's thickness),
//                           the default is outside the narrower range, or ''
//                           (blank: the option is left out, the core's default)
// Controls that compose options (size-mode and size-value, layer-mode,
// wall-on, fidelity-on, decimate-on, smooth) are the page's own, unmarked;
// one may take just its range from an option: data-range-of="<JS key>".
// Pure functions of text (no DOM): the build and Node tests use them.

/** An option's JS key in kebab-case, the id of its control: coreSize -> core-size. */
export const kebab = (js) => js.replace(/[A-Z]/g, (c) => `-${c.toLowerCase()}`);

/** The page's display units: the factor from the option's value to what the control shows. */
export const DISPLAY_UNITS = { percent: 100 };

const factorOf = (display) => {
  if (display && !(display in DISPLAY_UNITS)) throw new Error(`unknown display unit "${display}"`);
  return display ? DISPLAY_UNITS[display] : 1;
};

/** An option's value as a control in `display` units shows it (12
 * significant digits: 0.05 -> 5, not 5.000000000000001). */
export const toDisplay = (x, display) => Number((Number(x) * factorOf(display)).toPrecision(12));

/** A control's number in `display` units as the option's value. */
export const fromDisplay = (x, display) => x / factorOf(display);

const ATTRIBUTE = /([^\s"'=<>/]+)(?:\s*=\s*"([^"]*)")?/g;
const TAG = /<(input|select)\b((?:[^>"]|"[^"]*")*)>/g;
const OPTION = /<option\b((?:[^>"]|"[^"]*")*)>([\s\S]*?)<\/option>/g;

function parseAttributes(text) {
  const attrs = new Map();
  for (const [, name, value] of text.replace(/\/\s*$/, '').matchAll(ATTRIBUTE)) attrs.set(name, value ?? '');
  return attrs;
}

const writeAttributes = (attrs) => [...attrs].map(([name, value]) => (value === '' && BOOLEAN.has(name) ? name : `${name}="${value}"`)).join(' ');
const BOOLEAN = new Set(['checked', 'selected', 'disabled', 'hidden', 'readonly', 'required']);

/**
 * The inputs and selects of `html`: {tag, id, attrs (Map of the opening
 * tag's attributes), options (a select's: [{value, attrs, text}]), start,
 * end (the control's text range in html: the opening tag, or the whole
 * select)}.
 */
export function htmlControls(html) {
  const controls = [];
  for (const m of html.matchAll(TAG)) {
    const attrs = parseAttributes(m[2]);
    const control = { tag: m[1], id: attrs.get('id'), attrs, start: m.index, end: m.index + m[0].length, options: [] };
    if (m[1] === 'select') {
      const close = html.indexOf('</select>', control.end);
      for (const o of html.slice(control.end, close).matchAll(OPTION)) {
        const oattrs = parseAttributes(o[1]);
        control.options.push({ value: oattrs.get('value') ?? o[2].trim(), attrs: oattrs, text: o[2] });
      }
      control.end = close + '</select>'.length;
    }
    controls.push(control);
  }
  return controls;
}

/** The controls of `html` that take their range (and default) from an
 * option: data-option or data-range-of. */
export const optionControls = (html) => htmlControls(html).filter(({ attrs }) => attrs.has('data-option') || attrs.has('data-range-of'));

/** The option of the table with this JS key (or throws: a control names one that is not). */
export function optionSpec(table, js) {
  const spec = table.find((s) => s.js === js && s.faces.includes('js'));
  if (!spec) throw new Error(`no option with the JS key "${js}" in the option table`);
  return spec;
}

/**
 * What the table gives a control (its attributes as built): for a number
 * input {min, max, value, step?} (strings, in its display units; '' for
 * none), for a checkbox {checked}, for a select {selected: the default
 * choice}. data-range-of takes only the range.
 */
export function builtAttributes(table, control) {
  const { attrs } = control;
  const js = attrs.get('data-option') ?? attrs.get('data-range-of');
  const spec = optionSpec(table, js);
  const rangeOnly = !attrs.has('data-option');
  const display = attrs.get('data-display');
  const shown = (x) => (x === undefined || x === '' ? '' : String(toDisplay(x, display)));
  if (control.tag === 'select') return { selected: attrs.has('data-start') ? attrs.get('data-start') : spec.default };
  if (spec.type === 'flag') return { checked: spec.defaultOn };
  if (spec.type !== 'number' && spec.type !== 'integer') throw new Error(`${control.id}: the option ${js} is no number`);
  const built = {
    min: attrs.get('data-min') ?? shown(spec.min),
    max: attrs.get('data-max') ?? shown(spec.max),
  };
  if (!rangeOnly) built.value = attrs.has('data-start') ? attrs.get('data-start') : shown(spec.default);
  if (spec.type === 'integer') built.step = '1';
  return built;
}

/** `html` with every option control's range and default from `table`. */
export function withOptionTable(html, table) {
  let out = '';
  let at = 0;
  for (const control of optionControls(html)) {
    const built = builtAttributes(table, control);
    let text;
    if (control.tag === 'select') {
      // The opening tag and the text between the options (line breaks) kept.
      const open = html.indexOf('>', control.start) + 1;
      text =
        html.slice(control.start, open) +
        html.slice(open, control.end).replace(OPTION, (_, a, label) => {
          const attrs = parseAttributes(a);
          attrs.delete('selected');
          if ((attrs.get('value') ?? label.trim()) === built.selected) attrs.set('selected', '');
          return `<option ${writeAttributes(attrs)}>${label}</option>`;
        });
    } else {
      const attrs = new Map(control.attrs);
      for (const [name, value] of Object.entries(built)) {
        if (value === '' || value === false) attrs.delete(name);
        else attrs.set(name, value === true ? '' : value);
      }
      text = `<${control.tag} ${writeAttributes(attrs)} />`;
    }
    out += html.slice(at, control.start) + text;
    at = control.end;
  }
  return out + html.slice(at);
}
