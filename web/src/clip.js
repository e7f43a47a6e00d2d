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

/**
 * The face adjacency the view reads (`across`, one Int32Array entry per
 * face, 4 per tetrahedron, from the core: volume.across of a mesh result,
 * made by core/mesh/tet_face_adjacency.h): across[4t+f] is the tetrahedron
 * across face f of t, or, on the boundary, -1 - g with g the surface tag of
 * the boundary triangle there (UNKNOWN_TAG if no triangle matches).
 */
export const UNKNOWN_TAG = 0x7fff;

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
 * @param {Int32Array} across the face adjacency (volume.across; see UNKNOWN_TAG)
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
