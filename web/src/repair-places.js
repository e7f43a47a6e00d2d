// The places the preparation repaired, in the page's words: where the
// surface crossed itself and was re-surfaced (analysis.repairs.
// crossings_resurfaced, those resolved), and the damaged vessel ends
// trimmed back to a clean cross-section (repairs.damaged_ends), or left
// when the damage reaches too deep or the trim would take too much. Each is lettered (A, B, ...), as its
// mark in the view. Pure logic over the analysis (no DOM).
import { point, withUnit } from './units.js';

const count = (n) => Number(n).toLocaleString('en');
const plural = (n, one, many = `${one}s`) => `${count(n)} ${n === 1 ? one : many}`;

/** 'A', 'B', ... 'Z', 'AA', 'AB', ... for i = 0, 1, ... */
export const letter = (i) => (i < 26 ? '' : letter(Math.floor(i / 26) - 1)) + String.fromCharCode(65 + (i % 26));

/** What was wrong at a damaged end: '5 crossing, 2 folded or twisted, 14
 * around tiny loops' (triangles). */
function damage(end) {
  return [
    [end.crossing, 'crossing'],
    [end.misoriented, 'folded or twisted'],
    [end.nonmanifold, 'on non-manifold edges'],
    [end.tiny_loops, 'around tiny loops'],
  ]
    .filter(([n]) => n > 0)
    .map(([n, what]) => `${count(n)} ${what}`)
    .join(', ');
}

/**
 * The repaired places of `analysis`: [{id, kind: 'resurfaced' | 'trimmed'
 * | 'damaged', point, radius, what, text}] (what: a few words for the
 * mark's name; text: the list's sentence).
 * @param {object} analysis
 */
export function repairPlaces(analysis) {
  const r = analysis.repairs ?? {};
  const unit = analysis.units?.unit ?? '';
  const scale = analysis.bounding_box?.diagonal ?? 0;
  const at = (p) => `${point(p, scale)}${unit ? ` ${unit}` : ''}`;
  const items = [];
  for (const c of r.crossings_resurfaced ?? []) {
    if (!c.resolved) continue; // left for the damaged end it lies in, or said as a crossing
    const half = Math.hypot(...c.box_max.map((x, k) => x - c.box_min[k])) / 2;
    items.push({
      kind: 'resurfaced',
      point: c.where,
      radius: half,
      what: 're-surfaced where the surface crossed itself',
      text:
        `Re-surfaced where the surface crossed itself, at ${at(c.where)}: ` +
        `${plural(c.pairs, 'pair')} of crossing triangles, ${count(c.triangles_removed)} triangles replaced by ` +
        `${count(c.triangles_added)}.`,
    });
  }
  for (const e of r.damaged_ends ?? []) {
    const what = damage(e);
    const depth = Number((e.depth / e.radius).toPrecision(2));
    const end = `the damaged vessel end at ${at(e.where)} (radius ${withUnit(e.radius, unit).trim()}${what ? `; triangles ${what}` : ''})`;
    items.push(
      e.trimmed
        ? {
            kind: 'trimmed',
            point: e.point,
            radius: e.radius,
            what: 'a damaged vessel end, trimmed back',
            text: `Trimmed back ${depth} ${depth === 1 ? 'radius' : 'radii'} to a clean cross-section: ${end}.`,
          }
        : {
            kind: 'damaged',
            point: e.where,
            radius: e.radius,
            what: 'a damaged vessel end, not trimmed',
            text:
              `Not trimmed: ${end}, the damage reaching more than 3 radii in or the trim taking a fifth of the ` +
              'surface; add a cut across the vessel below it.',
          },
    );
  }
  return items.map((item, i) => ({ id: letter(i), ...item }));
}

/** The analysis' warnings the repaired places say already (the list says
 * them in the page's words, with their marks). */
export const saidAsRepair = (warning) =>
  /^the surface crossed itself at .*: re-surfaced there/.test(warning) || /^the vessel end at .* is damaged/.test(warning);
