// The numbers of a length legend (the size view's): the range a colormap
// spans over per-vertex values, and round tick values within it. Plain
// arrays, no DOM, so it is tested in Node (web/test/size-view.test.js).

/** The smallest and largest finite values of `values`: [min, max], or null
 * when there is none. */
export function valueRange(values) {
  let lo = Infinity;
  let hi = -Infinity;
  for (const x of values) {
    if (!Number.isFinite(x)) continue;
    if (x < lo) lo = x;
    if (x > hi) hi = x;
  }
  return lo <= hi ? [lo, hi] : null;
}

/**
 * Round values between lo and hi (both included when round themselves):
 * about `count` multiples of 1, 2 or 5 times a power of ten, ascending,
 * each within [lo, hi]. A range of one value gives [lo].
 */
export function niceTicks(lo, hi, count = 4) {
  if (!(hi > lo)) return [lo];
  const raw = (hi - lo) / Math.max(1, count);
  const power = 10 ** Math.floor(Math.log10(raw));
  const step = [1, 2, 5, 10].map((m) => m * power).find((s) => s >= raw) ?? 10 * power;
  const ticks = [];
  for (let k = Math.ceil(lo / step - 1e-9); k * step <= hi * (1 + 1e-12) + 1e-300; k++) {
    // Rounded to the step's digits: 0.30000000000000004 is 0.3.
    ticks.push(Number((k * step).toPrecision(12)));
  }
  return ticks;
}

/** Where `x` sits on a ramp from lo to hi, 0 to 1 (0.5 for a flat range). */
export const rampPosition = (x, lo, hi) => (hi > lo ? Math.min(1, Math.max(0, (x - lo) / (hi - lo))) : 0.5);
