// Whether the openings look right for a flow simulation, before meshing:
// one opening only (no outlet), a vessel end left closed (the core proposed
// to cut it, or proposes it still, and no opening is near it), openings so
// small that they are defect loops of the surface rather than vessel ends;
// and where the surface still crosses itself (with the repairs off: turn
// them on, they re-surface it; with them on, where they could not: a
// damaged end to trim, or a place to cut off). Pure logic over the analysis; the page shows the warnings
// by the openings and asks before meshing with openings that look wrong
// (`blocking`: opening-warnings.js).
import { crossingRemedy } from './remedies.js';
import { point, withUnit } from './units.js';

// An opening under this fraction of the largest one's radius is a defect
// loop, not a vessel end.
const TINY = 0.05;
// A proposed vessel end is open when an opening lies within this many of
// its radii (a cut moved along the vessel stays within 5).
const NEAR = 6;

const distance = (p, q) => Math.hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]);

/**
 * The warnings on the openings of `analysis`: [{id, text, places, remedy?,
 * blocking}] (remedy: a remedies.js remedy that fixes it, `ends` when its
 * places are vessel ends to cut open; blocking: asked about before
 * meshing), [] when they look right.
 * @param {object} analysis the shown analysis
 * @param {{proposals?: object[], prep?: object}} file the vessel ends
 *   proposed when the file was first analyzed (closed): {point, radius};
 *   the analyze options it was analyzed with (repair 'off')
 */
export function openingWarnings(analysis, { proposals = [], prep = {} } = {}) {
  const openings = analysis.openings ?? [];
  // A surface meshing refuses anyway (pieces, non-manifold): its refusal,
  // with its remedy, comes first; the openings are said, not asked about.
  const refused =
    analysis.components > 1 || analysis.nonmanifold_edges > 0 || analysis.nonmanifold_vertices > 0;
  const unit = analysis.units?.unit ?? '';
  const scale = analysis.bounding_box?.diagonal ?? 0;
  const warnings = [];
  const crossings = analysis.self_crossings?.places ?? [];
  if (crossings.length) {
    const off = prep.repair === 'off';
    const remedy = off ? { action: 'repair', places: crossings, value: 0 } : crossingRemedy(crossings, openings);
    const n = crossings.length;
    const where = n === 1 ? `at ${point(crossings[0], scale)} ${unit}` : `at ${n} places`;
    const end = remedy.action === 'trim_end' ? ', at a damaged vessel end' : '';
    const why = off ? ' (Repair is off: with it on, such places are re-surfaced or trimmed)' : '';
    warnings.push({
      id: 'self-crossing',
      text: `The surface crosses itself ${where} (marked in the view)${end}: meshing may fail there${why}.`,
      places: crossings,
      remedy,
      blocking: false,
    });
  }
  // The vessel ends proposed now and when the file was first analyzed,
  // each once.
  const seen = new Set();
  const proposed = [...(analysis.clip_proposals ?? []), ...proposals].filter((end) => {
    const key = end.point.map((x) => x.toPrecision(6)).join(',');
    return !seen.has(key) && seen.add(key);
  });
  if (!openings.length) {
    // Closed: no inlet nor outlet. Its vessel ends, when found, are the cuts.
    const ends = proposed.map((end) => end.point);
    warnings.push({
      id: 'no-opening',
      text:
        'The surface is closed: it has no opening to be an inlet or an outlet. ' +
        (ends.length ? 'Cut its vessel ends open.' : 'Add a cut on each vessel where it should end.'),
      places: [], // the proposed cuts are drawn already
      ...(ends.length && { remedy: { action: 'cut_here', places: ends, value: 0, ends: true } }),
      blocking: !refused,
    });
    return warnings;
  }
  const largest = Math.max(...openings.map((o) => o.radius));

  // Ends still proposed, and ends proposed at first that no opening is near.
  const open = (end) => openings.some((o) => distance(o.centroid, end.point) < NEAR * end.radius);
  const closed = proposed.filter((end) => !open(end));
  if (closed.length) {
    const widest = closed.reduce((a, b) => (b.radius > a.radius ? b : a));
    const wider = widest.radius > largest;
    const one = closed.length === 1;
    const where = one ? ` at ${point(widest.point, scale)} ${unit} (radius ${withUnit(widest.radius, unit)})` : '';
    warnings.push({
      id: 'closed-end',
      text:
        `${one ? 'A vessel end is' : `${closed.length} vessel ends are`} still closed${where}` +
        `${wider ? ': it is wider than every opening, so it is likely the inlet' : ''}.`,
      places: closed.map((end) => end.point),
      remedy: { action: 'cut_here', places: closed.map((end) => end.point), value: 0, ends: true },
      blocking: !refused,
    });
  }

  if (openings.length === 1) {
    warnings.push({
      id: 'no-outlet',
      text:
        'One opening only: the model has no outlet. Cut the other vessel ends open (Add a cut), ' +
        'or check the caps.',
      places: [],
      blocking: !refused,
    });
  }

  const tiny = openings.map((o, i) => ({ o, k: i + 1 })).filter(({ o }) => o.radius < TINY * largest);
  if (tiny.length) {
    const ks = tiny.map(({ k }) => k);
    const smallest = Math.min(...tiny.map(({ o }) => o.radius));
    warnings.push({
      id: 'tiny-openings',
      text:
        `${ks.length === 1 ? `Opening ${ks[0]} is` : `Openings ${ks.join(', ')} are`} tiny ` +
        `(radius down to ${withUnit(smallest, unit)}, under ${TINY * 100}% of the largest): ` +
        'defect loops of the surface rather than vessel ends; they would be capped as outlets.',
      places: tiny.map(({ o }) => o.centroid),
      blocking: !refused,
    });
  }
  return warnings;
}
