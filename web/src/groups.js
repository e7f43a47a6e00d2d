// Colors of the physical groups (surfaces: wall, inlet, outlet_k or the
// names given to the openings, and with a vessel wall outer_wall,
// wall_inlet, wall_outlet_k; volumes: lumen, boundary_layer, vessel_wall,
// also the colors of the faces cut by the clipping plane) and of the
// volume's parts, and their legends.
const FIXED = {
  wall: [0.8, 0.8, 0.78],
  inlet: [0.16, 0.42, 0.85],
  outer_wall: [0.74, 0.68, 0.5],
  lumen: [0.93, 0.56, 0.52],
  boundary_layer: [0.35, 0.68, 0.95],
  vessel_wall: [0.6, 0.16, 0.22],
};
const OUTLETS = [
  [0.22, 0.66, 0.32],
  [0.96, 0.6, 0.1],
  [0.58, 0.36, 0.78],
  [0.1, 0.66, 0.7],
  [0.86, 0.3, 0.56],
  [0.55, 0.5, 0.2],
];
const OTHER = [0.6, 0.6, 0.6];

/** A palette color for a name the user gave an opening (the same each time). */
function namedColor(name) {
  let h = 0;
  for (const ch of name) h = (h * 31 + ch.codePointAt(0)) >>> 0;
  return OUTLETS[h % OUTLETS.length];
}

/** RGB (0..1) of the group `name`; a wall ring (wall_inlet, wall_outlet_k,
 * wall_NAME) is its cap's color, paler; a cap the user named gets a palette
 * color. */
export function groupColor(name) {
  if (FIXED[name]) return FIXED[name];
  const ring = /^wall_(.+)$/.exec(name);
  if (ring) return groupColor(ring[1]).map((c) => 0.5 * c + 0.5);
  const outlet = /^outlet_(\d+)$/.exec(name);
  if (outlet) return OUTLETS[(Number(outlet[1]) - 1) % OUTLETS.length];
  return name ? namedColor(name) : OTHER;
}

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
  list.replaceChildren(...names.map((name) => legendItem(name, groupColor(name), { group: name })));
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
