// The palette of the physical groups (the openings' colours: their labels,
// their list rows' swatches, their caps in the mesh): 24 colours picked one
// by one, each the farthest (in CIELAB, the eye's distances) from the ones
// before it and from the wall's grey, the inlet's blue, the view's
// background and the errors' red, among colours light and saturated enough
// to read on the view.
// So neighbours in the list differ most, and no two of 24 groups look alike.

/** RGB (0..1) of the HSL color h (degrees), s, l (0..1). */
export function hsl(h, s, l) {
  const a = s * Math.min(l, 1 - l);
  const f = (n) => {
    const k = (n + h / 30) % 12;
    return l - a * Math.max(-1, Math.min(k - 3, 9 - k, 1));
  };
  return [f(0), f(8), f(4)];
}

/** CIELAB (D65) of an sRGB colour (0..1). */
export function lab(rgb) {
  const lin = rgb.map((c) => (c <= 0.04045 ? c / 12.92 : ((c + 0.055) / 1.055) ** 2.4));
  const x = (0.4124 * lin[0] + 0.3576 * lin[1] + 0.1805 * lin[2]) / 0.95047;
  const y = 0.2126 * lin[0] + 0.7152 * lin[1] + 0.0722 * lin[2];
  const z = (0.0193 * lin[0] + 0.1192 * lin[1] + 0.9505 * lin[2]) / 1.08883;
  const f = (t) => (t > 216 / 24389 ? Math.cbrt(t) : (24389 / 27 * t + 16) / 116);
  return [116 * f(y) - 16, 500 * (f(x) - f(y)), 200 * (f(y) - f(z))];
}

/** The distance of two colours as the eye sees it (CIE76 ΔE). */
export const deltaE = (a, b) => {
  const [p, q] = [lab(a), lab(b)];
  return Math.hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]);
};

export const PALETTE_SIZE = 24;

// Colours the palette keeps away from: the wall, the inlet, the background,
// the page's error red (a red label would read as an error).
const AVOID = [
  [0.8, 0.8, 0.78],
  [0.16, 0.42, 0.85],
  [0.914, 0.929, 0.945],
  [0.7, 0.15, 0.18],
];

function pick() {
  const candidates = [];
  for (let h = 0; h < 360; h += 7.5) {
    for (const s of [0.5, 0.65, 0.8]) for (const l of [0.32, 0.44, 0.56, 0.68]) candidates.push(hsl(h, s, l));
  }
  const labs = candidates.map(lab);
  const nearest = labs.map((c) => Math.min(...AVOID.map((a) => dist(c, lab(a)))));
  const chosen = [];
  while (chosen.length < PALETTE_SIZE) {
    let best = 0;
    for (let i = 1; i < candidates.length; i++) if (nearest[i] > nearest[best]) best = i;
    chosen.push(candidates[best]);
    for (let i = 0; i < candidates.length; i++) nearest[i] = Math.min(nearest[i], dist(labs[i], labs[best]));
  }
  return chosen;
}

function dist(p, q) {
  return Math.hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]);
}

/** The palette: PALETTE_SIZE RGB triples (0..1), all different. */
export const PALETTE = pick();

/** The palette's color number i (any integer; it repeats after 24). */
export const paletteColor = (i) => PALETTE[((i % PALETTE_SIZE) + PALETTE_SIZE) % PALETTE_SIZE];
