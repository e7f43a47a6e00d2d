// Kept boundary-layer prisms, shown in the clipped view as the tetrahedra
// they split into (the smallest-index diagonal rule of core/mesh/prism_split,
// so neighbors agree) and their quads at the openings as two triangles each
// (cut from the smallest id, as the prisms' faces are): the view then works
// on tetrahedra only. The MSH file keeps the prisms.

// The orientation-preserving relabelings bringing each vertex to 0.
const ROTATION = [
  [0, 1, 2, 3, 4, 5],
  [1, 2, 0, 4, 5, 3],
  [2, 0, 1, 5, 3, 4],
  [3, 5, 4, 0, 2, 1],
  [4, 3, 5, 1, 0, 2],
  [5, 4, 3, 2, 1, 0],
];

/** The 3 tetrahedra of prism v (6 ids) into out at offset o (12 ids). */
function splitPrism(v, out, o) {
  let first = 0;
  for (let k = 1; k < 6; k++) if (v[k] < v[first]) first = k;
  const r = ROTATION[first].map((k) => v[k]);
  const tets =
    Math.min(r[1], r[5]) < Math.min(r[2], r[4])
      ? [r[0], r[1], r[2], r[5], r[0], r[1], r[5], r[4], r[0], r[4], r[5], r[3]]
      : [r[0], r[1], r[2], r[4], r[0], r[4], r[2], r[5], r[0], r[4], r[5], r[3]];
  out.set(tets, o);
}

/** gamma_t of tetrahedron (a, b, c, d) given as point indices. */
function gammaT(p, a, b, c, d) {
  const P = (i, k) => p[3 * i + k];
  const sub = (i, j) => [P(i, 0) - P(j, 0), P(i, 1) - P(j, 1), P(i, 2) - P(j, 2)];
  const cross = (u, w) => [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]];
  const dot = (u, w) => u[0] * w[0] + u[1] * w[1] + u[2] * w[2];
  const len = (u) => Math.sqrt(dot(u, u));
  const v6 = dot(cross(sub(b, a), sub(c, a)), sub(d, a));
  const area = (i, j, k) => 0.5 * len(cross(sub(j, i), sub(k, i)));
  const faces = area(a, b, c) + area(a, b, d) + area(a, c, d) + area(b, c, d);
  const edges = [sub(a, b), sub(a, c), sub(a, d), sub(b, c), sub(b, d), sub(c, d)].map(len);
  const denom = faces * Math.max(...edges);
  return denom > 0 ? (Math.sqrt(6) * v6) / denom : 0;
}

/**
 * A volume with kept prisms (volume.prisms) as one of tetrahedra only:
 * the prisms split (their part: 2 in the vessel wall's region, else 1) and
 * the quads split; the other fields kept. Volumes without prisms are
 * returned as they are.
 */
export function withPrismsSplit(volume) {
  if (!volume?.prisms?.length) return volume;
  const { positions, tets, tetQuality, tetRegion, prisms, prismRegion, quads, quadTag } = volume;
  const nt = tets.length / 4;
  const np = prisms.length / 6;
  const outTets = new Uint32Array(4 * (nt + 3 * np));
  outTets.set(tets);
  const quality = new Float32Array(nt + 3 * np);
  quality.set(tetQuality);
  const region = new Int32Array(nt + 3 * np);
  region.set(tetRegion);
  const part = new Uint8Array(nt + 3 * np);
  part.set(volume.tetPart ?? new Uint8Array(nt));
  const wall = volume.regionNames.indexOf('vessel_wall');
  for (let p = 0; p < np; p++) {
    const o = 4 * (nt + 3 * p);
    splitPrism(prisms.subarray(6 * p, 6 * p + 6), outTets, o);
    for (let k = 0; k < 3; k++) {
      const t = nt + 3 * p + k;
      const q = o + 4 * k;
      quality[t] = gammaT(positions, outTets[q], outTets[q + 1], outTets[q + 2], outTets[q + 3]);
      region[t] = prismRegion[p];
      part[t] = prismRegion[p] === wall ? 2 : 1;
    }
  }
  const nq = quads.length / 4;
  const triangles = new Uint32Array(volume.triangles.length + 6 * nq);
  triangles.set(volume.triangles);
  const triangleTag = new Int32Array(volume.triangleTag.length + 2 * nq);
  triangleTag.set(volume.triangleTag);
  let o = volume.triangles.length;
  for (let q = 0; q < nq; q++) {
    const [a, b, c, d] = quads.subarray(4 * q, 4 * q + 4);
    const m = Math.min(a, b, c, d);
    triangles.set(m === a || m === c ? [a, b, c, a, c, d] : [b, c, d, b, d, a], o);
    o += 6;
    triangleTag[volume.triangleTag.length + 2 * q] = quadTag[q];
    triangleTag[volume.triangleTag.length + 2 * q + 1] = quadTag[q];
  }
  return { ...volume, tets: outTets, tetQuality: quality, tetRegion: region, tetPart: part, triangles, triangleTag };
}
