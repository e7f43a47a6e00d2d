// Quality colormap for gamma in [0, 1]: red (degenerate) through yellow to
// green and blue (equilateral).
const STOPS = [
  [0.0, [0.78, 0.1, 0.12]],
  [0.3, [0.95, 0.55, 0.1]],
  [0.55, [0.95, 0.88, 0.25]],
  [0.8, [0.35, 0.75, 0.4]],
  [1.0, [0.2, 0.45, 0.8]],
];

// Sequential colormap for lengths (the vessel radius, the edge size): dark
// blue (small) through teal and green to yellow (large), even in lightness
// so that a larger value always looks lighter.
const SCALAR_STOPS = [
  [0.0, [0.27, 0.0, 0.33]],
  [0.25, [0.23, 0.32, 0.55]],
  [0.5, [0.13, 0.57, 0.55]],
  [0.75, [0.37, 0.79, 0.38]],
  [1.0, [0.99, 0.91, 0.14]],
];

/** Writes the RGB (0..1) color at x in [0, 1] of the colormap `stops`
 * ([x, [r, g, b]] by increasing x; linear between them) into
 * out[offset..offset+3). */
function stopsColor(stops, x, out, offset) {
  let i = 1;
  while (i < stops.length - 1 && x > stops[i][0]) i++;
  const [x0, c0] = stops[i - 1];
  const [x1, c1] = stops[i];
  const t = (x - x0) / (x1 - x0);
  for (let k = 0; k < 3; k++) out[offset + k] = c0[k] + t * (c1[k] - c0[k]);
}

/** CSS linear-gradient of the colormap `stops`, for a legend. */
function stopsGradientCss(stops) {
  const css = stops.map(([x, c]) => {
    const rgb = c.map((v) => Math.round(v * 255)).join(',');
    return `rgb(${rgb}) ${Math.round(x * 100)}%`;
  });
  return `linear-gradient(to right, ${css.join(', ')})`;
}

/** Writes the RGB (0..1) color of quality q into out[offset..offset+3). */
export function qualityColor(q, out, offset = 0) {
  stopsColor(STOPS, Math.min(1, Math.max(0, q)), out, offset);
}

/** CSS linear-gradient of the colormap, for the legend. */
export function qualityGradientCss() {
  return stopsGradientCss(STOPS);
}

/** Writes the RGB (0..1) color of t in [0, 1] (clamped) on the length
 * colormap into out[offset..offset+3). */
export function scalarColor(t, out, offset = 0) {
  stopsColor(SCALAR_STOPS, Math.min(1, Math.max(0, Number.isFinite(t) ? t : 0)), out, offset);
}

/** CSS linear-gradient of the length colormap, for its legend. */
export function scalarGradientCss() {
  return stopsGradientCss(SCALAR_STOPS);
}
