// The clipped view of a tetrahedral mesh, as Gmsh draws it: keep the
// tetrahedra whose centroid lies on one side of a plane and draw the faces of
// the kept set that are not shared by two kept tetrahedra (the kept part of
// the boundary and the cut faces). Plain typed arrays, no three.js, so it runs
// (and is tested) anywhere.
//
// Face f of tetrahedron t is the face opposite its vertex f, listed so that
// its normal points out of t (tets have positive orientation:
// ((b-a)x(c-a)).(d-a) > 0). A copy of the core's face table (kFaceOut in
// core/mesh/volume_mesh.h); web/test/clip-faces.test.js compares them.
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
 * vertex triples: each face (the 4 of every tet, then the tagged boundary
 * triangles) goes into the bucket of its smallest vertex (a counting sort),
 * and within a bucket equal pairs of other vertices meet in a small hash
 * table. O(faces) in typed arrays; no string or object keys. Needs
 * vertexCount < 2^26 (keys exact in doubles).
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
  // Face i: its smallest vertex, and its two others as one exact number.
  const lo = new Uint32Array(total);
  const rest = new Float64Array(total); // mid * vertexCount + hi < 2^53
  const put = (i, a, b, c) => {
    let t;
    if (a > b) (t = a), (a = b), (b = t);
    if (b > c) (t = b), (b = c), (c = t);
    if (a > b) (t = a), (a = b), (b = t);
    lo[i] = a;
    rest[i] = b * vertexCount + c;
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
  // Counting sort by the smallest vertex; each bucket keeps its faces' keys
  // next to their ids, so matching a bucket reads contiguous memory.
  const start = new Uint32Array(vertexCount + 1);
  for (let i = 0; i < total; i++) start[lo[i] + 1]++;
  for (let v = 0; v < vertexCount; v++) start[v + 1] += start[v];
  const order = new Uint32Array(total);
  const keys = new Float64Array(total);
  const fill = start.slice(0, vertexCount);
  for (let i = 0; i < total; i++) {
    const j = fill[lo[i]]++;
    order[j] = i;
    keys[j] = rest[i];
  }

  // Match equal triples in each bucket with a small open-addressing table
  // (cleared for free: a slot counts only if stamped with the bucket's v).
  let maxBucket = 1;
  for (let v = 0; v < vertexCount; v++) maxBucket = Math.max(maxBucket, start[v + 1] - start[v]);
  const bits = 32 - Math.clz32(2 * maxBucket - 1);
  const mask = (1 << bits) - 1;
  const shift = 32 - bits;
  const slotFace = new Uint32Array(mask + 1);
  const slotKey = new Float64Array(mask + 1);
  const slotStamp = new Uint32Array(mask + 1);
  const across = new Int32Array(tetFaces).fill(-1 - UNKNOWN_TAG);
  for (let v = 0; v < vertexCount; v++) {
    const stamp = v + 1;
    // A bucket lists its tet faces before its boundary triangles (the
    // scatter is stable), so a triangle always meets its tet face here.
    for (let j = start[v], e = start[v + 1]; j < e; j++) {
      const f = order[j];
      const k = keys[j];
      const high = Math.imul((k / 4294967296) | 0, 0x85ebca6b);
      let h = Math.imul((k >>> 0) ^ high, 0x9e3779b1) >>> shift;
      while (slotStamp[h] === stamp && slotKey[h] !== k) h = (h + 1) & mask;
      if (slotStamp[h] !== stamp) {
        slotStamp[h] = stamp;
        slotKey[h] = k;
        slotFace[h] = f;
        continue;
      }
      const g = slotFace[h]; // the first face with this triple
      if (g >= tetFaces) continue; // a triangle that is no tet's face
      if (f >= tetFaces) {
        // A boundary triangle: its tag goes to its (unpaired) tet face.
        if (across[g] < 0) across[g] = -1 - (triangleTag ? triangleTag[f - tetFaces] : 0);
      } else if (across[g] === -1 - UNKNOWN_TAG) {
        across[g] = f >> 2; // two tets share the face
        across[f] = g >> 2;
      }
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
    this.cutByPart = [0, 0, 0]; // cut faces per part of their tet (with tetPart)
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
 * cutColor or, with cutTetColors (3 bytes per tet), the color of its tet;
 * with tetColors (3 bytes per tet) every face takes the color of its tet.
 * With tetPart (one part 0..2 per tet), out.cutByPart counts the cut faces
 * of each part.
 * @param {{positions: Float32Array, tets: Uint32Array}} mesh
 * @param {Int32Array} across from faceAdjacency
 * @param {Float32Array} centroid from tetCentroids
 * @param {{value: number, flip?: boolean, tetColors?: Uint8Array,
 *   tagColors: Uint8Array, cutColor: number[], cutTetColors?: Uint8Array,
 *   tetPart?: Uint8Array}} options
 * @param {ClipBuffers} out
 */
export function clipBoundary(mesh, across, centroid, options, out) {
  const { positions, tets } = mesh;
  const { value, flip = false, tetColors = null, tagColors, cutColor } = options;
  const { cutTetColors = null, tetPart = null } = options;
  const cutByPart = out.cutByPart.fill(0);
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
      } else if (u >= 0 && cutTetColors) {
        r = cutTetColors[3 * t];
        g = cutTetColors[3 * t + 1];
        b = cutTetColors[3 * t + 2];
      } else if (u >= 0) {
        [r, g, b] = cutColor;
      } else {
        const tag = Math.min(-1 - u, unknown - 1);
        r = tagColors[3 * tag];
        g = tagColors[3 * tag + 1];
        b = tagColors[3 * tag + 2];
      }
      if (u >= 0) {
        cut++;
        if (tetPart) cutByPart[tetPart[t]]++;
      }
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
