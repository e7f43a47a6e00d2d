// A test input for the clipped view: the cube [0, n]^3 split into n^3 unit
// cubes of 6 positively oriented tetrahedra each (Kuhn: the paths along the
// edges from corner 000 to 111), with its boundary triangles tagged by side
// (0: x = 0, 1: x = n, 2: y = 0, ..., 5: z = n). And the brute-force face
// map the tests check the clipped view's adjacency against.
import { TET_FACES } from '../src/clip.js';

/** The faces of the tetrahedra (face f of t: TET_FACES[f], outward) by their
 * sorted vertices ("a,b,c"): the ids 4 t + f that have each, the faces in
 * order of first appearance. */
export function facesByVertices(tets) {
  const faces = new Map();
  for (let t = 0; t < tets.length / 4; t++) {
    TET_FACES.forEach((f, i) => {
      const key = f.map((k) => tets[4 * t + k]).sort((a, b) => a - b).join();
      if (!faces.has(key)) faces.set(key, []);
      faces.get(key).push(4 * t + i);
    });
  }
  return faces;
}

/** @returns {{positions: Float32Array, tets: Uint32Array, triangles:
 *   Uint32Array, triangleTag: Int32Array, vertexCount: number}} */
export function kuhnGrid(n, { boundary = true } = {}) {
  const m = n + 1;
  const id = (i, j, k) => i + m * (j + m * k);
  const positions = new Float32Array(3 * m * m * m);
  for (let k = 0; k < m; k++) {
    for (let j = 0; j < m; j++) {
      for (let i = 0; i < m; i++) positions.set([i, j, k], 3 * id(i, j, k));
    }
  }
  const paths = [
    [0, 1, 2],
    [0, 2, 1],
    [1, 0, 2],
    [1, 2, 0],
    [2, 0, 1],
    [2, 1, 0],
  ];
  const tets = new Uint32Array(24 * n * n * n);
  let t = 0;
  for (let k = 0; k < n; k++) {
    for (let j = 0; j < n; j++) {
      for (let i = 0; i < n; i++) {
        for (const [p, q, r] of paths) {
          const c = [i, j, k];
          const corners = [id(...c)];
          for (const axis of [p, q, r]) {
            c[axis]++;
            corners.push(id(...c));
          }
          // Odd permutations are negatively oriented: swap two corners.
          const odd = (p > q) + (p > r) + (q > r);
          if (odd % 2) [corners[2], corners[3]] = [corners[3], corners[2]];
          tets.set(corners, 4 * t++);
        }
      }
    }
  }
  const result = { positions, tets, vertexCount: m * m * m };
  if (!boundary) return result;
  // Boundary: the faces of one tet only, outward (opposite corner inside).
  const faces = [...facesByVertices(tets).values()]
    .filter((ids) => ids.length === 1)
    .map(([f]) => TET_FACES[f % 4].map((x) => tets[f - (f % 4) + x]));
  const triangles = new Uint32Array(3 * faces.length);
  const triangleTag = new Int32Array(faces.length);
  faces.forEach((tri, b) => {
    triangles.set(tri, 3 * b);
    for (let axis = 0; axis < 3; axis++) {
      const x = tri.map((v) => positions[3 * v + axis]);
      if (x.every((y) => y === 0)) triangleTag[b] = 2 * axis;
      if (x.every((y) => y === n)) triangleTag[b] = 2 * axis + 1;
    }
  });
  return { ...result, triangles, triangleTag };
}
