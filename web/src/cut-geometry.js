// The small vector geometry of the Prepare step's cuts (plain arrays
// [x, y, z], no three.js, so it runs and is tested anywhere): a cut's plane
// as the core's clipPlanes take it, its normal tilted by two angles, the
// point a move along the vessel asks the core about.

const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const scale = (a, s) => a.map((x) => x * s);
const add = (a, b) => a.map((x, i) => x + b[i]);

/** `a` of unit length (unchanged when it is zero). */
export function normalize(a) {
  const n = Math.hypot(...a);
  return n > 0 ? scale(a, 1 / n) : a;
}

/**
 * Two unit axes u, v perpendicular to the unit normal n (u, v, n
 * right-handed), the same for the same n: u is n x the coordinate axis least
 * aligned with n.
 */
export function tiltAxes(n) {
  const k = [0, 1, 2].reduce((best, i) => (Math.abs(n[i]) < Math.abs(n[best]) ? i : best), 0);
  const e = [0, 0, 0];
  e[k] = 1;
  const u = normalize(cross(n, e));
  return [u, cross(n, u)];
}

/** `a` rotated by `angle` radians about the unit axis `k` (Rodrigues). */
function rotate(a, k, angle) {
  const c = Math.cos(angle);
  const s = Math.sin(angle);
  return add(add(scale(a, c), scale(cross(k, a), s)), scale(k, dot(k, a) * (1 - c)));
}

/**
 * The unit normal `n` tilted by `a` degrees about its first tilt axis, then
 * by `b` degrees about its second (tiltAxes).
 */
export function tilted(n, [a, b] = [0, 0]) {
  if (!a && !b) return normalize(n);
  const m = normalize(n);
  const [u, v] = tiltAxes(m);
  const rad = Math.PI / 180;
  return normalize(rotate(rotate(m, u, a * rad), v, b * rad));
}

/** The plane [x, y, z, nx, ny, nz] of a cut {point, normal, tilt}: the
 * core's clipPlanes entry (the normal points to the side removed). */
export const cutPlane = ({ point, normal, tilt }) => [...point, ...tilted(normal, tilt)];

/** The point `t` local radii from the cut's point along its (untilted)
 * normal: where to ask for the cut moved along the vessel. */
export const alongVessel = ({ point, normal, radius }, t) => add(point, scale(normalize(normal), t * radius));

/**
 * A cut the core found near an old one, its normal turned to the old one's
 * side (the core turns it toward the smaller side, which flips when a cut
 * moves past the middle of a vessel).
 */
export function keepSide(found, old) {
  return dot(found.normal, old.normal) < 0 ? { ...found, normal: scale(found.normal, -1) } : found;
}
