// What the user can do about a refusal, as a control: the API's
// Failure.remedy {action, places, value} when the core gives one (layers
// that cannot grow: no_layers; crossings, non-manifold or non-orientable
// surfaces with repair off: repair; several pieces: largest_component),
// else read from the message, for the refusals that carry none yet: the
// element budget (a coarser size), a crossing left with repair on (trim the
// damaged end, or cut there), a patch too folded (smooth), a closed surface
// (its proposed cuts), the unit. This is the one place that maps messages
// to remedies (remedyOf: the `fromMessage` fallback), to go as the core
// gives the rest. Each remedy has the label of the button that applies it,
// in the page's words. Pure logic (no DOM): the page applies them
// (remedy-actions.js).
import { withUnit } from './units.js';

/** The actions of the API's vocabulary, in the order they are offered. */
export const ACTIONS = ['trim_end', 'cut_here', 'repair', 'largest_component', 'smooth', 'coarser', 'no_layers', 'units'];

// A number as the core writes it, and a point "(x, y, z)".
const NUM = String.raw`-?\d+(?:\.\d+)?(?:e[-+]?\d+)?`;
const TRIPLE = new RegExp(String.raw`\((${NUM}), (${NUM}), (${NUM})\)`, 'g');

/** The points "(x, y, z)" a message names, in order. */
export function placesIn(message) {
  return [...String(message).matchAll(TRIPLE)].map((m) => [Number(m[1]), Number(m[2]), Number(m[3])]);
}

/**
 * The coarser size that fits the element budget a refusal names ("makes
 * about 1.32e+04 triangles on the wall, more than the element budget
 * (maxElements 1000)"), from the size asked: triangles go as 1/h^2 and as
 * N^2, tetrahedra as 1/h^3; 10% under the budget. null when the message
 * does not say.
 * @param {string} message
 * @param {{mode: string, value: number}} size the size asked ('size' h, or
 *   'perCircumference' N; a core size refusal: 'coreSize')
 */
export function fittingSize(message, size) {
  const m = new RegExp(String.raw`about (${NUM}) (triangles|tetrahedra).*?\(maxElements (${NUM})\)`).exec(message);
  if (!m || !size || !(size.value > 0)) return null;
  const ratio = Number(m[1]) / (0.9 * Number(m[3]));
  if (!(ratio > 1)) return null;
  if (size.mode === 'perCircumference') {
    // N shrinks with the square root of the triangles (and of the tetrahedra, roughly).
    const n = Math.floor(size.value / Math.sqrt(ratio));
    return n >= 3 ? { mode: 'perCircumference', value: n } : null;
  }
  const power = m[2] === 'triangles' ? 1 / 2 : 1 / 3;
  return { mode: size.mode, value: Number((size.value * ratio ** power).toPrecision(2)) };
}

// A self-crossing within this many radii of an opening is a damaged end;
// openings under this fraction of the largest are defect loops, no ends.
const END_RADII = 3;
const TINY_END = 0.05;

/**
 * What to do about the places where the surface crosses itself: near an
 * opening, the end is damaged (where a vessel met the image border):
 * trimmed back; elsewhere, cut there.
 * @param {number[][]} places
 * @param {{centroid: number[], radius: number}[]} openings
 */
export function crossingRemedy(places, openings = []) {
  // Vessel ends only: not the tiny defect loops a crossing may leave.
  const largest = Math.max(0, ...openings.map((o) => o.radius));
  const end = (p) =>
    openings.findIndex(
      (o) => o.radius >= TINY_END * largest && Math.hypot(...o.centroid.map((x, k) => x - p[k])) < END_RADII * o.radius,
    );
  const ends = places.map(end);
  if (!places.length || ends.includes(-1)) return { action: 'cut_here', places, value: 0 };
  // One trim an end, at its first crossing.
  return { action: 'trim_end', places: places.filter((_, i) => ends.indexOf(ends[i]) === i), value: 0 };
}

/**
 * A remedy read from a message of a refusal the core gives no remedy for:
 * {action, places, value} (and for `coarser` the size `mode` its value is
 * in), or null.
 * @param {{error: string, option?: string}} failure
 * @param {{size?: {mode: string, value: number}, proposals?: number[][],
 *   openings?: object[]}} context the size asked; the vessel ends the
 *   analysis proposes to cut; its openings ({centroid, radius})
 */
export function fromMessage({ error = '', option }, { size, proposals = [], openings = [] } = {}) {
  const places = placesIn(error);
  if (/element budget/.test(error)) {
    const mode = option === 'coreSize' ? 'coreSize' : size?.mode;
    const fit = fittingSize(error, mode === 'coreSize' ? { mode, value: size?.core } : size);
    return fit && { action: 'coarser', places: [], value: fit.value, mode: fit.mode };
  }
  if (/crosses itself/.test(error)) return crossingRemedy(places.slice(0, 1), openings);
  if (/too folded there/.test(error)) return { action: 'smooth', places, value: 10 };
  if (/surface is closed|no opening/.test(error) && proposals.length) {
    return { action: 'cut_here', places: proposals, value: 0 };
  }
  if (/\bsay units\b|guessed unit/.test(error)) return { action: 'units', places: [], value: 0 };
  return null;
}

/**
 * The remedy of a failure: the core's own (`failure.remedy`, when its
 * action is one the page knows), else the one its message implies, else
 * null.
 */
export function remedyOf(failure, context = {}) {
  const given = failure?.remedy;
  if (given && ACTIONS.includes(given.action)) {
    return { action: given.action, places: given.places ?? [], value: given.value ?? 0 };
  }
  return failure?.error ? fromMessage(failure, context) : null;
}

/** Whether applying `remedy` changes the preparation (the surface is
 * analyzed again) rather than the mesh options (meshed again). */
export const preparesAgain = (remedy) =>
  ['trim_end', 'cut_here', 'repair', 'largest_component', 'smooth', 'units'].includes(remedy.action);

/**
 * The label of the button that applies `remedy`, in the page's words:
 * 'Trim the damaged end', 'Cut here', 'Cut the 3 vessel ends open' (its
 * places are vessel ends: `ends`), 'Use a coarser size (h = 0.5 mm)'.
 * @param {{action: string, places?: number[][], value?: number, mode?: string, ends?: boolean}} remedy
 * @param {{unit?: string}} model
 */
export function remedyLabel(remedy, { unit = '' } = {}) {
  const n = remedy.places?.length ?? 0;
  switch (remedy.action) {
    case 'trim_end':
      return n > 1 ? `Trim the ${n} damaged ends` : 'Trim the damaged end';
    case 'cut_here':
      if (remedy.ends) return n > 1 ? `Cut the ${n} vessel ends open` : 'Cut the vessel end open';
      return n > 1 ? `Cut at these ${n} places` : 'Cut here';
    case 'coarser':
      if (remedy.mode === 'perCircumference') return `Use a coarser size (N = ${remedy.value})`;
      if (remedy.mode === 'coreSize') return `Use a coarser core size (${withUnit(remedy.value, unit)})`;
      return `Use a coarser size (h = ${withUnit(remedy.value, unit)})`;
    case 'no_layers':
      return 'Mesh without layers here';
    case 'smooth':
      return `Smooth the surface (${remedy.value || 10} passes)`;
    case 'repair':
      return 'Repair the surface';
    case 'largest_component':
      return 'Keep the largest piece only';
    case 'units':
      return 'Choose the units';
    default:
      return '';
  }
}
