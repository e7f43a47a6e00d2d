// The palette of the physical groups: 24 colors of evenly spaced hues (15°
// apart) with alternating lightness, in an order that puts far hues next to
// each other, so the first few groups differ most and no two of up to 24
// groups share a color.

/** RGB (0..1) of the HSL color h (degrees), s, l (0..1). */
export function hsl(h, s, l) {
  const a = s * Math.min(l, 1 - l);
  const f = (n) => {
    const k = (n + h / 30) % 12;
    return l - a * Math.max(-1, Math.min(k - 3, 9 - k, 1));
  };
  return [f(0), f(8), f(4)];
}

export const PALETTE_SIZE = 24;
// 7 is prime to 24: i -> 7i mod 24 visits every hue once, 105° apart.
const STRIDE = 7;

/** The palette: PALETTE_SIZE RGB triples (0..1), all different. */
export const PALETTE = Array.from({ length: PALETTE_SIZE }, (_, i) => {
  const hue = (i * STRIDE) % PALETTE_SIZE;
  // Neighbouring hues (15° apart) differ in lightness.
  return hsl(hue * (360 / PALETTE_SIZE), 0.72, hue % 2 ? 0.68 : 0.42);
});

/** The palette's color number i (any integer; it repeats after 24). */
export const paletteColor = (i) => PALETTE[((i % PALETTE_SIZE) + PALETTE_SIZE) % PALETTE_SIZE];
