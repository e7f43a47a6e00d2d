// The clipped view of a tetrahedral mesh, as Gmsh draws it: keep the
// tetrahedra whose centroid lies on one side of a plane and draw the faces of
// the kept set that are not shared by two kept tetrahedra (the kept part of
// the boundary and the cut faces). Plain typed arrays, no three.js, so it runs
// (and is tested) anywhere.
//
// Face f of tetrahedron t is the face opposite its vertex f, listed so that
// its normal points out of t (tets have positive orientation:
// ((b-a)x(c-a)).(d-a) > 0).
export const TET_FACES = [
  [1, 2, 3],
  [0, 3, 2],
  [0, 1, 3],
  [0, 2, 1],
];

/** Encodes "no neighbor, boundary face with surface tag g" as -1 - g. */
export const UNKNOWN_TAG = 0x7fff;

/**
 * The face adjacency of a conforming tetrahedral mesh, matched on sorted
 * vertex triples: each face (the 4 of every tet and the tagged boundary
 * triangles) goes into the bucket of its smallest vertex (a counting sort),
 * and a bucket's faces are sorted by their two other vertices, so equal
 * triples end up side by side. O(faces) with sequential passes; no string or
 * object keys.
 * @param {Uint32Array} tets 4 vertex indices per tetrahedron
 * @param {number} vertexCount
 * @param {Uint32Array} [triangles] boundary triangles, 3 indices each
 * @param {Int32Array} [triangleTag] one surface tag per boundary triangle
 * @returns {Int32Array} across[4t+f]: the tetrahedron across face f of t, or,
 *   on the boundary, -1 - g with g the tag of the boundary triangle there
 *   (UNKNOWN_TAG if no triangle matches).
 */
export function faceAdjacency(tets, vertexCount, triangles = new Uint32Array(0), triangleTag) {
  const tetFaces = tets.length; // 4 per tet
  const total = tetFaces + triangles.length / 3;
  // Sorted corners (lo < mid < hi) of face i.
  const lo = new Uint32Array(total);
  const mid = new Uint32Array(total);
  const hi = new Uint32Array(total);
  const put = (i, a, b, c) => {
    if (a > b) [a, b] = [b, a];
    if (b > c) [b, c] = [c, b];
    if (a > b) [a, b] = [b, a];
    lo[i] = a;
    mid[i] = b;
    hi[i] = c;
  };
  for (let t = 0; t < tetFaces; t += 4) {
    const a = tets[t];
    const b = tets[t + 1];
    const c = tets[t + 2];
    const d = tets[t + 3];
    put(t, b, c, d);
    put(t + 1, a, c, d);
    put(t + 2, a, b, d);
    put(t + 3, a, b, c);
  }
  for (let i = tetFaces, k = 0; i < total; i++, k += 3) {
    put(i, triangles[k], triangles[k + 1], triangles[k + 2]);
  }
  // Counting sort by the smallest vertex.
  const start = new Uint32Array(vertexCount + 1);
  for (let i = 0; i < total; i++) start[lo[i] + 1]++;
  for (let v = 0; v < vertexCount; v++) start[v + 1] += start[v];
  const order = new Uint32Array(total);
  const fill = start.slice(0, vertexCount);
  for (let i = 0; i < total; i++) order[fill[lo[i]]++] = i;

  const across = new Int32Array(tetFaces).fill(-1 - UNKNOWN_TAG);
  const key = (i) => mid[i] * vertexCount + hi[i]; // exact below 2^53
  for (let v = 0; v < vertexCount; v++) {
    const s = start[v];
    const e = start[v + 1];
    // Insertion sort of the bucket by (mid, hi): buckets hold ~20 faces.
    for (let j = s + 1; j < e; j++) {
      const f = order[j];
      const k = key(f);
      let m = j - 1;
      while (m >= s && key(order[m]) > k) {
        order[m + 1] = order[m];
        m--;
      }
      order[m + 1] = f;
    }
    // Runs of equal triples: two tet faces are neighbors; a tet face and a
    // boundary triangle give the face its tag.
    for (let j = s; j < e; ) {
      const k = key(order[j]);
      let r = j + 1;
      while (r < e && key(order[r]) === k) r++;
      let first = -1;
      let tag = UNKNOWN_TAG;
      for (let m = j; m < r; m++) {
        const f = order[m];
        if (f >= tetFaces) tag = triangleTag ? triangleTag[f - tetFaces] : 0;
      }
      for (let m = j; m < r; m++) {
        const f = order[m];
        if (f >= tetFaces) continue;
        if (first < 0) {
          first = f;
          across[f] = -1 - tag;
        } else {
          across[first] = f >> 2;
          across[f] = first >> 2;
          first = -1;
        }
      }
      j = r;
    }
  }
  return across;
}

/** Coordinate `axis` (0, 1, 2) of every tetrahedron's centroid. */
export function tetCentroids(positions, tets, axis) {
  const out = new Float32Array(tets.length / 4);
  for (let t = 0, i = 0; i < tets.length; t++, i += 4) {
    out[t] =
      0.25 *
      (positions[3 * tets[i] + axis] +
        positions[3 * tets[i + 1] + axis] +
        positions[3 * tets[i + 2] + axis] +
        positions[3 * tets[i + 3] + axis]);
  }
  return out;
}

/**
 * Growable output of clipBoundary, reused between calls so a slider move
 * allocates nothing once the buffers are large enough: 3 corners of
 * `count` triangles, positions (xyz floats) and colors (rgb bytes).
 */
export class ClipBuffers {
  constructor(triangles = 1024) {
    this.positions = new Float32Array(9 * triangles);
    this.colors = new Uint8Array(9 * triangles);
    this.count = 0; // triangles written
    this.cut = 0; // of which cut faces (inside the mesh)
    this.grown = true; // the arrays were replaced since the last call
  }

  get capacity() {
    return this.positions.length / 9;
  }

  grow() {
    const n = Math.ceil(this.capacity * 1.5) + 1024;
    const positions = new Float32Array(9 * n);
    positions.set(this.positions);
    const colors = new Uint8Array(9 * n);
    colors.set(this.colors);
    this.positions = positions;
    this.colors = colors;
    this.grown = true;
  }
}

/**
 * Writes the clipped boundary into `out`: the faces of the kept tetrahedra
 * (centroid <= value along the axis, or >= value when `flip`) that are not
 * shared with another kept tetrahedron, each oriented out of its tet.
 * Colors: a boundary face with tag g takes tagColors[3g..], a cut face
 * cutColor, unless tetColors is given (3 bytes per tet: every face the color
 * of its tet).
 * @param {{positions: Float32Array, tets: Uint32Array}} mesh
 * @param {Int32Array} across from faceAdjacency
 * @param {Float32Array} centroid from tetCentroids
 * @param {{value: number, flip?: boolean, tetColors?: Uint8Array,
 *   tagColors: Uint8Array, cutColor: number[]}} options
 * @param {ClipBuffers} out
 */
export function clipBoundary(mesh, across, centroid, options, out) {
  const { positions, tets } = mesh;
  const { value, flip = false, tetColors = null, tagColors, cutColor } = options;
  const nt = centroid.length;
  const unknown = tagColors.length / 3; // colored like the last tag
  out.grown = false;
  let n = 0;
  let cut = 0;
  let P = out.positions;
  let C = out.colors;
  let capacity = out.capacity;
  for (let t = 0; t < nt; t++) {
    if (flip ? !(centroid[t] >= value) : !(centroid[t] <= value)) continue;
    for (let f = 0; f < 4; f++) {
      const u = across[4 * t + f];
      if (u >= 0 && (flip ? centroid[u] >= value : centroid[u] <= value)) continue;
      if (n === capacity) {
        out.grow();
        P = out.positions;
        C = out.colors;
        capacity = out.capacity;
      }
      let r;
      let g;
      let b;
      if (tetColors) {
        r = tetColors[3 * t];
        g = tetColors[3 * t + 1];
        b = tetColors[3 * t + 2];
      } else if (u >= 0) {
        [r, g, b] = cutColor;
      } else {
        const tag = Math.min(-1 - u, unknown - 1);
        r = tagColors[3 * tag];
        g = tagColors[3 * tag + 1];
        b = tagColors[3 * tag + 2];
      }
      if (u >= 0) cut++;
      const corners = TET_FACES[f];
      for (let k = 0; k < 3; k++) {
        const v = 3 * tets[4 * t + corners[k]];
        const o = 9 * n + 3 * k;
        P[o] = positions[v];
        P[o + 1] = positions[v + 1];
        P[o + 2] = positions[v + 2];
        C[o] = r;
        C[o + 1] = g;
        C[o + 2] = b;
      }
      n++;
    }
  }
  out.count = n;
  out.cut = cut;
  return out;
}
