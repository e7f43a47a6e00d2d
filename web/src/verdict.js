// The verdict on a mesh: ready for CFD, or the things to check, each with
// its places. It covers the element count, the worst tetrahedra and wall
// triangles (and where they are, found in the mesh itself), the boundary
// layer's coverage, the volume change against the input and the mesh's
// warnings. Pure logic over a mesh() result (no DOM): verdict-view.js
// shows it.
import { placesIn } from './remedies.js';
import { inPageWords } from './words.js';

/** What a mesh must meet to be called ready (the items say them). */
export const LIMITS = {
  // gamma_t of a core tetrahedron: below it, solvers' gradients degrade.
  tet: 0.1,
  // gamma_k of a wall triangle.
  triangle: 0.2,
  // Wall fraction with the boundary layer's full thickness (within 10%).
  layer: 0.9,
  // |volume change| of the remeshed wall against the input.
  volume: 0.03,
};
// Places are elements grouped in cells of this fraction of the model.
const CELL = 1 / 25;
const MAX_PLACES = 3;

const count = (n) => Number(n).toLocaleString('en');
const percent = (x) => `${(100 * x).toFixed(1)}%`;
const gamma = (x) => x.toFixed(2);

/**
 * The places of the elements whose quality is below `limit`: their
 * centroids grouped in cells of `cell` (model unit), the most crowded
 * first (at most MAX_PLACES), each {point, radius, count}. Also the worst
 * element's place (worst) even when none is below.
 * @param {Float32Array} positions 3 floats a vertex
 * @param {Uint32Array} elements `size` indices an element
 * @param {Float32Array} quality one value an element
 * @param {(e: number) => boolean} counted which elements count
 */
export function placesBelow({ positions, elements, size, quality, limit, cell, counted = () => true }) {
  const cells = new Map();
  let worst = -1;
  const centroid = (e) => {
    const c = [0, 0, 0];
    for (let k = 0; k < size; k++) {
      for (let a = 0; a < 3; a++) c[a] += positions[3 * elements[size * e + k] + a] / size;
    }
    return c;
  };
  for (let e = 0; e < quality.length; e++) {
    if (!counted(e)) continue;
    if (worst < 0 || quality[e] < quality[worst]) worst = e;
    if (!(quality[e] < limit)) continue;
    const c = centroid(e);
    const key = c.map((x) => Math.floor(x / cell)).join(',');
    const entry = cells.get(key) ?? { sum: [0, 0, 0], count: 0 };
    for (let a = 0; a < 3; a++) entry.sum[a] += c[a];
    entry.count++;
    cells.set(key, entry);
  }
  const places = [...cells.values()]
    .sort((a, b) => b.count - a.count)
    .slice(0, MAX_PLACES)
    .map(({ sum, count: n }) => ({ point: sum.map((s) => s / n), radius: cell, count: n }));
  const below = [...cells.values()].reduce((n, c) => n + c.count, 0);
  const worstPlace = worst < 0 ? null : { point: centroid(worst), radius: cell, quality: quality[worst] };
  return { below, places, worst: worstPlace };
}

/**
 * The verdict on a mesh() result (its report, and its volume and surface
 * for the places): {ready, title, items: [{id, level: 'ok' | 'check' |
 * 'note', text, places: [{point, radius, what}]}]}.
 * @param {{report: object, volume?: object, surface?: object}} result
 * @param {{unit?: string, scale?: number}} model
 */
export function meshVerdict(result, { unit = '', scale = 1 } = {}) {
  const out = result.report.output;
  const v = out.volume;
  const cell = Math.max(scale, 1e-12) * CELL;
  const items = [];

  const tets = v ? v.tetrahedra : 0;
  const prisms = result.volume?.prisms ? result.volume.prisms.length / 6 : 0;
  const elements = out.groups.reduce((n, g) => n + g.elements, 0);
  items.push({
    id: 'elements',
    level: 'ok',
    text: v
      ? `${count(elements)} elements: ${count(tets)} tetrahedra` +
        `${prisms ? ` (${count(prisms)} layer prisms kept)` : ''}, ${count(out.triangles)} wall triangles.`
      : `${count(out.triangles)} wall triangles (surface only: no volume).`,
    places: [],
  });

  // The worst tetrahedra (of the core: the layers' are flat by design) and
  // wall triangles, and where those below the limit are.
  const vol = v ? result.volume : null;
  const part = vol?.tetPart;
  const layered = Boolean(part?.some((p) => p > 0));
  const kinds = [
    vol && {
      id: 'tets',
      mesh: { positions: vol.positions, elements: vol.tets, size: 4, quality: vol.tetQuality },
      counted: part ? (e) => part[e] === 0 : undefined,
      words: { what: 'tetrahedra', one: 'tetrahedron', symbol: 'γt', limit: LIMITS.tet },
      scope: layered ? ' of the core (the flat layer elements are flat by design)' : '',
    },
    result.surface?.quality?.length && {
      id: 'triangles',
      mesh: { positions: result.surface.positions, elements: result.surface.triangles, size: 3, quality: result.surface.quality },
      words: { what: 'wall triangles', one: 'wall triangle', symbol: 'γk', limit: LIMITS.triangle },
      scope: '',
    },
  ].filter(Boolean);
  for (const { id, mesh, counted, words, scope } of kinds) {
    const found = placesBelow({ ...mesh, limit: words.limit, cell, counted });
    items.push(qualityItem(id, found, { ...words, scope }));
  }

  const layer = v?.boundary_layer;
  if (layer) {
    const full = layer.thickness_within_10pct;
    items.push({
      id: 'layer',
      level: full >= LIMITS.layer ? 'ok' : 'check',
      text:
        full >= LIMITS.layer
          ? `Boundary layer: ${layer.layers} layer${layer.layers === 1 ? '' : 's'} at full thickness ` +
            `on ${percent(full)} of the wall.`
          : `Boundary layer thinned: full thickness on only ${percent(full)} of the wall ` +
            `(reduced on ${percent(layer.reduced_area_fraction)}, where fronts meet or bends are tight).`,
      places: [],
    });
  } else if (v) {
    items.push({
      id: 'layer',
      level: 'note',
      text: 'No boundary layer: the wall shear stress is less accurate without one.',
      places: [],
    });
  }

  const change = out.remesh?.fidelity?.volume_change;
  if (typeof change === 'number') {
    const signed = `${change > 0 ? '+' : change < 0 ? '−' : ''}${percent(Math.abs(change))}`;
    items.push({
      id: 'volume',
      level: Math.abs(change) <= LIMITS.volume ? 'ok' : 'check',
      text:
        Math.abs(change) <= LIMITS.volume
          ? `Volume: ${signed} against the input (within ${percent(LIMITS.volume)}).`
          : `Volume: ${signed} against the input (over ${percent(LIMITS.volume)}): ` +
            'a smaller size follows the vessels better.',
      places: [],
    });
  }

  // The meshing's own warnings (the preparation's are said with the
  // input), with the places they name (a layer grown after the wall was
  // relaxed there).
  const prepared = new Set(result.report.input?.warnings ?? []);
  const warnings = (result.report.warnings ?? []).filter((w) => !prepared.has(w));
  for (const [i, w] of warnings.entries()) {
    const places = placesIn(w).map((point) => ({ point, radius: cell, what: 'named in the warning' }));
    items.push({ id: `warning-${i + 1}`, level: 'check', text: inPageWords(w, { unit, scale }), places });
  }

  const checks = items.filter((i) => i.level === 'check').length;
  return {
    ready: checks === 0,
    title: checks === 0 ? 'Ready for CFD' : `Check ${checks === 1 ? 'this' : `these ${checks} things`} before CFD`,
    items,
  };
}

/** The item on the worst elements of one kind: fine, or how many are below
 * the limit and where (the most crowded places). */
function qualityItem(id, { below, places, worst }, { what, one, symbol, limit, scope }) {
  if (!worst) return { id, level: 'ok', text: `No ${what}.`, places: [] };
  if (below === 0) {
    return {
      id,
      level: 'ok',
      text: `Worst ${one}${scope}: ${symbol} ${gamma(worst.quality)} (at least ${limit}).`,
      places: [
        { point: worst.point, radius: worst.radius, what: `the worst ${one}, ${symbol} ${gamma(worst.quality)}` },
      ],
    };
  }
  return {
    id,
    level: 'check',
    text: `${count(below)} ${what}${scope} below ${symbol} ${limit} (worst ${gamma(worst.quality)}), ` +
      `${places.length === 1 ? 'in one place' : `most in ${places.length} places`}.`,
    places: places.map((p) => ({
      point: p.point,
      radius: p.radius,
      what: `${count(p.count)} ${what} below ${symbol} ${limit}`,
    })),
  };
}

/** What the input's minimum triangle quality means, when it needs saying:
 * needles (γ near 0) are the input's, and remeshing removes them. */
export function inputQualityNote(quality) {
  if (!quality || !(quality.min < 0.01)) return '';
  return 'Needle triangles in the input (γ near 0): remeshing removes them.';
}
