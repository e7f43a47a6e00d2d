// Colors of the physical groups (wall, inlet, outlet_k, and lumen for the
// faces cut by the clipping plane), and their legend.
const FIXED = {
  wall: [0.8, 0.8, 0.78],
  inlet: [0.16, 0.42, 0.85],
  lumen: [0.93, 0.56, 0.52],
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

/** RGB (0..1) of the group `name`. */
export function groupColor(name) {
  if (FIXED[name]) return FIXED[name];
  const outlet = /^outlet_(\d+)$/.exec(name);
  return outlet ? OUTLETS[(Number(outlet[1]) - 1) % OUTLETS.length] : OTHER;
}

const css = (rgb) => `rgb(${rgb.map((v) => Math.round(v * 255)).join(',')})`;

/** Fills the <ul> legend with one swatch per group name. */
export function drawGroupLegend(list, names) {
  list.replaceChildren(
    ...names.map((name) => {
      const li = document.createElement('li');
      li.dataset.group = name;
      const swatch = document.createElement('span');
      swatch.className = 'swatch';
      swatch.style.background = css(groupColor(name));
      li.append(swatch, name);
      return li;
    }),
  );
}
