// A generated vessel tree with 10 open ends, as a binary STL: a trunk along
// z (radius 1) with 8 side branches (radius 0.5, two on each side, rising
// gently), voxelized (a mask of the union of the tubes, voxel 0.125) and
// its boundary written face by face (the staircase of an unsmoothed
// segmentation). The tubes run through the box's walls, where no face is
// written: the 10 vessel ends are open (flat, on the box's faces).

const HALF = 6; // the box: x, y in [-6, 6], z in [0, 16]
const HEIGHT = 16;

/** The tubes: [start, unit direction, length, radius]; `spiral` side
 * branches around the trunk (0: the 8 of the four sides). */
function tubes(spiral = 0) {
  const out = [[[0, 0, -1], [0, 0, 1], HEIGHT + 2, 1]];
  if (spiral > 0) {
    // From z = 1.5 to 13.5, a golden angle apart: neighbours in z point far apart.
    for (let k = 0; k < spiral; k++) {
      const angle = k * 2.39996;
      const n = Math.hypot(1, 0.12);
      out.push([[0, 0, 1.5 + (12 * k) / Math.max(1, spiral - 1)], [Math.cos(angle) / n, Math.sin(angle) / n, 0.12 / n], 12, 0.5]);
    }
    return out;
  }
  const sides = [
    [1, 0],
    [0, 1],
    [-1, 0],
    [0, -1],
  ];
  for (let k = 0; k < 8; k++) {
    const [dx, dy] = sides[k % 4];
    const n = Math.hypot(1, 0.3);
    out.push([[0, 0, 2.5 + 1.5 * k], [dx / n, dy / n, 0.3 / n], 10, 0.5]);
  }
  return out;
}

/** Distance from p to the segment (start, direction, length), below the radius. */
function inside(p, list) {
  for (const [a, d, length, r] of list) {
    const v = [p[0] - a[0], p[1] - a[1], p[2] - a[2]];
    const t = Math.max(0, Math.min(length, v[0] * d[0] + v[1] * d[1] + v[2] * d[2]));
    const q = [v[0] - t * d[0], v[1] - t * d[1], v[2] - t * d[2]];
    if (q[0] * q[0] + q[1] * q[1] + q[2] * q[2] <= r * r) return true;
  }
  return false;
}

/** The tree's binary STL (Buffer) and its number of vessel ends (10, or
 * 2 + spiral). */
export function treeStl(voxel = 0.125, { spiral = 0 } = {}) {
  const list = tubes(spiral);
  const stl = voxelStl((p) => inside(p, list), { min: [-HALF, -HALF, 0], size: [2 * HALF, 2 * HALF, HEIGHT], voxel });
  return { stl, ends: 1 + 1 + (spiral || 8) };
}

/**
 * The boundary of the voxels of the box (`min`, `size`, cut in cubes of
 * `voxel`) whose centres are `isInside`, face by face, as a binary STL
 * (Buffer), outward. No face is written on the box's own walls: a shape
 * that runs through them is open there; one inside the box is closed.
 * @param {(p: number[]) => boolean} isInside
 */
export function voxelStl(isInside, { min, size, voxel }) {
  const dims = size.map((s) => Math.round(s / voxel));
  const [nx, ny, nz] = dims;
  const at = (i, j, k) => (i * ny + j) * nz + k;
  const mask = new Uint8Array(nx * ny * nz);
  for (let i = 0; i < nx; i++) {
    for (let j = 0; j < ny; j++) {
      for (let k = 0; k < nz; k++) mask[at(i, j, k)] = isInside([i, j, k].map((c, a) => min[a] + (c + 0.5) * voxel)) ? 1 : 0;
    }
  }
  const solid = (c) => c.every((x, a) => x >= 0 && x < dims[a]) && mask[at(...c)] === 1;
  const outside = (c) => c.every((x, a) => x >= 0 && x < dims[a]) && mask[at(...c)] === 0; // the box's walls are neither
  const corner = (c) => c.map((x, a) => min[a] + x * voxel);
  const triangles = [];
  for (let i = 0; i < nx; i++) {
    for (let j = 0; j < ny; j++) {
      for (let k = 0; k < nz; k++) {
        if (!mask[at(i, j, k)]) continue;
        for (let axis = 0; axis < 3; axis++) {
          for (const side of [0, 1]) {
            const n = [i, j, k];
            n[axis] += side ? 1 : -1;
            if (!outside(n) || solid(n)) continue;
            // The face between the voxel and n, its corners counter-clockwise seen from outside.
            const [u, w] = [(axis + 1) % 3, (axis + 2) % 3];
            const base = [i, j, k];
            base[axis] += side;
            const c = (du, dw) => {
              const p = [...base];
              p[u] += du;
              p[w] += dw;
              return corner(p);
            };
            const quad = side ? [c(0, 0), c(1, 0), c(1, 1), c(0, 1)] : [c(0, 0), c(0, 1), c(1, 1), c(1, 0)];
            triangles.push([quad[0], quad[1], quad[2]], [quad[0], quad[2], quad[3]]);
          }
        }
      }
    }
  }
  return stlOf(triangles, 'vesselmesh e2e voxels');
}

/** A binary STL (Buffer) of triangles [[x, y, z] x 3]. */
export function stlOf(triangles, header = 'vesselmesh e2e') {
  const buf = Buffer.alloc(84 + 50 * triangles.length);
  buf.write(header, 0);
  buf.writeUInt32LE(triangles.length, 80);
  triangles.forEach((t, f) => t.forEach((v, c) => v.forEach((x, a) => buf.writeFloatLE(x, 84 + 50 * f + 12 + 12 * c + 4 * a))));
  return buf;
}
