// Colors of the physical groups (surfaces: wall, inlet, outlet_k or the
// names given to the openings, and with a vessel wall outer_wall,
// wall_inlet, wall_outlet_k; volumes: lumen, boundary_layer, vessel_wall,
// also the colors of the faces cut by the clipping plane) and of the
// volume's parts, and their legends.
import { PALETTE_SIZE, paletteColor } from './palette.js';

const FIXED = {
  wall: [0.8, 0.8, 0.78],
  inlet: [0.16, 0.42, 0.85],
  outer_wall: [0.74, 0.68, 0.5],
  lumen: [0.93, 0.56, 0.52],
  boundary_layer: [0.35, 0.68, 0.95],
  vessel_wall: [0.6, 0.16, 0.22],
};
const OTHER = [0.6, 0.6, 0.6];

/** The palette number of outlet_k (k - 1), or null for another name. */
function outletIndex(name) {
  const outlet = /^outlet_(\d+)$/.exec(name);
  return outlet ? Number(outlet[1]) - 1 : null;
}

/**
 * The colors (RGB 0..1) of the groups `names`, all different for up to 24
 * groups: the fixed ones (wall, inlet, lumen...) their own; outlet_k the
 * palette's k-th; a cap the user named the first palette color no other
 * group of the list has; a wall ring (wall_inlet, wall_outlet_k, wall_NAME)
 * its cap's color, paler.
 */
export function groupColors(names) {
  const taken = new Set(names.map(outletIndex).filter((i) => i !== null));
  const named = new Map();
  let next = 0;
  const base = (name) => {
    if (FIXED[name]) return FIXED[name];
    const k = outletIndex(name);
    if (k !== null) return paletteColor(k);
    if (!name) return OTHER;
    if (!named.has(name)) {
      while (taken.has(next % PALETTE_SIZE) && next < taken.size + PALETTE_SIZE) next++;
      taken.add(next % PALETTE_SIZE);
      named.set(name, paletteColor(next++));
    }
    return named.get(name);
  };
  const color = (name) => {
    const ring = /^wall_(.+)$/.exec(name);
    return ring && !FIXED[name] ? color(ring[1]).map((c) => 0.5 * c + 0.5) : base(name);
  };
  // Caps first, so a ring listed before its cap gets the cap's color.
  for (const name of names) if (!/^wall_/.test(name)) base(name);
  return names.map(color);
}

/** RGB (0..1) of the group `name` alone (see groupColors). */
export const groupColor = (name) => groupColors([name])[0];

/** The volume's parts (volume.tetPart values): name and color. */
export const PARTS = [
  { name: 'core', color: FIXED.lumen },
  { name: 'boundary layer', color: FIXED.boundary_layer },
  { name: 'vessel wall', color: FIXED.vessel_wall },
];

const css = (rgb) => `rgb(${rgb.map((v) => Math.round(v * 255)).join(',')})`;

function legendItem(name, color, data) {
  const li = document.createElement('li');
  Object.assign(li.dataset, data);
  const swatch = document.createElement('span');
  swatch.className = 'swatch';
  swatch.style.background = css(color);
  li.append(swatch, name);
  return li;
}

/** Fills the <ul> legend with one swatch per group name. */
export function drawGroupLegend(list, names) {
  const colors = groupColors(names);
  list.replaceChildren(...names.map((name, i) => legendItem(name, colors[i], { group: name })));
}

/**
 * Fills the <ul> legend with one swatch per part that has tetrahedra.
 * @param {number[]} counts tetrahedra per part (PARTS order)
 */
export function drawPartLegend(list, counts) {
  list.replaceChildren(
    ...PARTS.flatMap(({ name, color }, part) => {
      if (!counts[part]) return [];
      const li = legendItem(name, color, { part: String(part) });
      li.title = `${counts[part].toLocaleString('en')} tetrahedra`;
      return [li];
    }),
  );
}

/**
 * The group legend's fold (a <details> around it): its summary counts the
 * groups; for a new mesh (a new `key`) it opens when the legend is short
 * and the view wide, so it never covers the model on a phone.
 */
export function foldLegend(details, count, key) {
  details.querySelector('summary').textContent = `Groups (${count})`;
  if (!details.dataset.watched) {
    // Narrowed to a phone's width: folded.
    details.dataset.watched = 'true';
    globalThis.matchMedia?.('(min-width: 700px)').addEventListener('change', (e) => {
      if (!e.matches) details.open = false;
    });
  }
  if (details.dataset.key === key) return;
  details.dataset.key = key;
  details.open = count <= 8 && Boolean(globalThis.matchMedia?.('(min-width: 700px)').matches);
}
