// The mesh and export options as a shareable link: the settings that differ
// from the page's defaults, in the URL's hash (#size-mode=size&layers=2).
// Opening such a link sets those controls (the link wins over what this
// browser remembered; the controls it does not name get their defaults);
// a value that no control accepts is ignored and said, in the page's words
// (the controls' names and choices as the panel shows them, never the
// API's option names). Per-file choices (units, cuts, opening names) are
// not in the link. A setting's key is its control's id, which for a
// control of one option is the option's JS key in kebab-case
// (option-controls.js); the keys of controls since renamed are still read
// (LINK_ALIASES), so old links keep working. The functions here are pure
// (tested in Node) but controlName; the page gives them its controls' specs.

/** The keys older links (and remembered settings) used for controls since
 * renamed to their option's key: old key -> id. */
export const LINK_ALIASES = { 'keep-prisms': 'prisms', 'export-format': 'format' };

/** The id a link's (or the remembered settings') key stands for. */
export const settingId = (key) => LINK_ALIASES[key] ?? key;

/** Remembered settings ({key: value}) by the controls' ids: those kept
 * under an old key renamed (where the new key is not there too). */
export const byCurrentIds = (saved) => ({
  ...Object.fromEntries(Object.entries(saved).map(([key, value]) => [settingId(key), value])),
  ...saved,
});

/**
 * A control's name as the panel shows it: its data-setting-name, else its
 * label's own text (without the control, hints and a trailing
 * parenthesis), after its fieldset's legend when that is not in it:
 * 'Size', 'Boundary layer: Layers', 'Keep prisms'.
 * @param {HTMLElement} el
 */
export function controlName(el) {
  const label = el.labels?.[0];
  const own = (node) =>
    node.nodeType === 3 ||
    (node.nodeType === 1 && !['INPUT', 'SELECT', 'TEXTAREA', 'BUTTON'].includes(node.tagName) && !node.classList.contains('hint'));
  const text = label ? [...label.childNodes].filter(own).map((n) => n.textContent).join('') : '';
  const name =
    el.dataset.settingName ??
    (text.replace(/\s+/g, ' ').replace(/\s*\([^)]*\)\s*$/, '').trim() || el.getAttribute('aria-label') || el.id);
  const legend = el.closest('fieldset')?.querySelector('legend')?.textContent.trim();
  return legend && !name.toLowerCase().includes(legend.toLowerCase()) ? `${legend}: ${name}` : name;
}

/**
 * A control's spec, from the element: {id, name (controlName), kind:
 * 'checkbox'|'select'|'number'|'text', options (select values) and labels
 * (their texts), min, max, integer, empty (blank allowed: its default is
 * blank)}.
 * @param {HTMLInputElement|HTMLSelectElement} el
 * @param {string|boolean} byDefault the control's default value
 */
export function controlSpec(el, byDefault) {
  const name = controlName(el);
  if (el.type === 'checkbox') return { id: el.id, name, kind: 'checkbox' };
  if (el.tagName === 'SELECT') {
    const options = [...el.options];
    return { id: el.id, name, kind: 'select', options: options.map((o) => o.value), labels: options.map((o) => o.textContent.trim()) };
  }
  if (el.type !== 'number') return { id: el.id, name, kind: 'text' };
  const bound = (s) => (s === '' ? undefined : Number(s));
  return {
    id: el.id,
    name,
    kind: 'number',
    min: bound(el.min),
    max: bound(el.max),
    integer: el.step === '1',
    empty: byDefault === '',
  };
}

/** Why `text` is not a value of the control `spec`, or null; `value` is
 * the control's value it stands for. */
export function parseValue(spec, text) {
  if (spec.kind === 'checkbox') {
    if (['1', 'true', 'on', 'yes'].includes(text)) return { value: true };
    if (['0', 'false', 'off', 'no'].includes(text)) return { value: false };
    return { problem: 'on or off (1 or 0)' };
  }
  if (spec.kind === 'select') {
    const choices = (spec.labels ?? spec.options).filter((_, i) => spec.options[i]).map((c) => `“${c}”`);
    return spec.options.includes(text) ? { value: text } : { problem: `one of ${choices.join(', ')}` };
  }
  if (spec.kind === 'number') {
    const range =
      spec.min !== undefined && spec.max !== undefined
        ? ` from ${spec.min} to ${spec.max}`
        : spec.min !== undefined
          ? ` of at least ${spec.min}`
          : '';
    const what = `${spec.integer ? 'a whole number' : 'a number'}${range}`;
    if (text.trim() === '') return spec.empty ? { value: '' } : { problem: what };
    const x = Number(text);
    if (!Number.isFinite(x) || (spec.integer && !Number.isInteger(x))) return { problem: what };
    if ((spec.min !== undefined && x < spec.min) || (spec.max !== undefined && x > spec.max)) return { problem: what };
    return { value: text.trim() };
  }
  return { value: text };
}

const encodeValue = (v) => (v === true ? '1' : v === false ? '0' : String(v));

/**
 * The hash of a link with `values` (id -> value): only those that differ
 * from `defaults`, in the order of `ids`; '' when all are the defaults.
 * @param {string[]} ids
 * @param {Map<string, string|boolean>|object} values
 * @param {Map<string, string|boolean>|object} defaults
 */
export function encodeSettings(ids, values, defaults) {
  const get = (m, id) => (m instanceof Map ? m.get(id) : m[id]);
  const params = new URLSearchParams();
  for (const id of ids) {
    const v = get(values, id);
    if (v === undefined || v === get(defaults, id)) continue;
    params.append(id, encodeValue(v));
  }
  const text = params.toString();
  return text ? `#${text}` : '';
}

/**
 * The settings in a link's hash: {values: {id: value} of those accepted,
 * problems: ['“Name” set to “value”: what it must be'] of those ignored
 * (named as the page names their controls), given: whether the hash holds
 * any setting at all}.
 * @param {string} hash location.hash ('#a=1&b=2', or '')
 * @param {object[]} specs controlSpec() of each remembered control
 */
export function decodeSettings(hash, specs) {
  const params = new URLSearchParams(hash.replace(/^#/, ''));
  const byId = new Map(specs.map((s) => [s.id, s]));
  const values = {};
  const problems = [];
  let given = false;
  for (const [key, text] of params) {
    given = true;
    const name = byId.has(key) ? key : settingId(key);
    const spec = byId.get(name);
    if (!spec) {
      problems.push(`“${key}”: not an option of this page`);
      continue;
    }
    const { value, problem } = parseValue(spec, text);
    if (problem) problems.push(`“${spec.name ?? name}” set to “${text}”: must be ${problem}`);
    else values[name] = value;
  }
  return { values, problems, given };
}

/** The notice said when a link's settings were ignored. */
export function ignoredNotice(problems) {
  if (!problems.length) return '';
  const n = problems.length;
  return `The link's ${n === 1 ? 'setting' : `${n} settings`} ${problems.join('; ')} — ignored (${n === 1 ? 'its default is used' : 'their defaults are used'}).`;
}

/** The notice said when a link was opened: the options whose value it
 * changed from this browser's (`names`: their controls' names) and those
 * it had that were ignored; '' when there is nothing to say (the page's
 * own address reloaded). */
export function linkNotice(names, problems) {
  const set = names.length ? `The link changed these options: ${names.map((n) => `“${n}”`).join(', ')}.` : '';
  return [set, ignoredNotice(problems)].filter(Boolean).join(' ');
}
