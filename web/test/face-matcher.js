// The face matcher web/src/clip.js had before the core returned the clipped
// view's adjacency (volume.across, core/mesh/tet_face_adjacency.h through
// wasm/bindings.cpp), kept verbatim as the tests' reference: the core's
// array must equal what it gives, and the tests of clip.js's pure
// functions on generated grids take their adjacency from it.
import { UNKNOWN_TAG } from '../src/clip.js';

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

