// The length unit of the loaded model as the page says it: the summary's
// text, the question asked only when the core's guess is not certain, and
// lengths with their unit.

const WORDS = { mm: 'millimetres', cm: 'centimetres', m: 'metres' };
// The other unit a guess could be, when the core names none.
const ALTERNATIVE = { mm: 'cm', cm: 'mm', m: 'mm' };

/** A length as the panel shows it: 4 significant digits, no trailing zeros
 * after the decimal point (2500, 6.25, 0.003273, 1.235e+5). */
export const length = (x) =>
  Number(x)
    .toPrecision(4)
    .replace(/(\.\d*?)0+($|e)/, '$1$2')
    .replace(/\.($|e)/, '$1');

/** A length and its unit: '6.265 mm'. */
export const withUnit = (x, unit) => `${length(x)} ${unit}`;

/** A point as '(x, y, z)', coordinates within 1e-6 `scale` of 0 shown as 0
 * (rounding noise of a centred model: -8.86e-18). */
export const point = (p, scale = 0) => `(${p.map((x) => length(Math.abs(x) <= 1e-6 * scale ? 0 : x)).join(', ')})`;

/**
 * The summary's text of analysis.units {unit, guessed, certain, reason}:
 * 'mm' (given), 'm (guessed from the median vessel radius 0.00327)',
 * 'mm? (not sure: median vessel radius 0.994)'.
 */
export function unitsText({ unit, guessed, certain, reason }) {
  if (!guessed) return unit;
  if (certain) return `${unit} (guessed from the ${reason})`;
  return `${unit}? (a guess from the ${reason})`;
}

/**
 * The question to ask while the core is unsure of the unit (until the
 * user says it), or null when the unit was given or the core is certain
 * (metres: radii of millimetres; the summary says how it was guessed):
 * 'Units: mm? The numbers could also be centimetres (median vessel radius 0.994).'.
 */
export function unitsQuestion({ unit, guessed, certain, reason, alternative }) {
  if (!guessed || certain) return null;
  const other = WORDS[alternative || ALTERNATIVE[unit]] ?? 'another unit';
  return `Units: ${unit}? The numbers could also be ${other}${reason ? ` (${reason})` : ''}.`;
}

/** The analyze (or mesh) options `prep` with the unit `guess` ({unit}) when
 * they give none: the first guess of a file, kept for it. */
export const withUnitGuess = (prep, guess) => (prep.units || !guess ? prep : { ...prep, units: guess.unit });
