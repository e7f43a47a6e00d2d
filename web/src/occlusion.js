// Whether a model point is hidden behind the shown surface, for the labels
// and marks drawn over the view (view-marks.js): the segment from the
// camera to the point is tested against the surface's triangles, found
// through a uniform grid of cells (Amanatides and Woo's traversal, "A fast
// voxel traversal algorithm for ray tracing", Eurographics 1987) and
// Moeller and Trumbore's segment-triangle test. Built once per surface,
// O(triangles); a test visits the cells along the segment only. Plain
// typed arrays, no three.js (tested in Node).

// About this many triangles a cell, and at most this many cells.
const PER_CELL = 2;
const MAX_CELLS = 1 << 18;
// A hit this close to the point's end of the segment (a fraction of its
// length) is the point's own surface, not something in front of it.
const END_SLACK = 1e-4;

export class Occluder {
  /**
   * @param {ArrayLike<number>} positions 3 numbers a vertex
   * @param {ArrayLike<number>} triangles 3 vertex indices a triangle
   */
  constructor(positions, triangles) {
    this.positions = positions;
    this.triangles = triangles;
    const nt = Math.floor(triangles.length / 3);
    const lo = [Infinity, Infinity, Infinity];
    const hi = [-Infinity, -Infinity, -Infinity];
    for (let i = 0; i < positions.length; i += 3) {
      for (let a = 0; a < 3; a++) {
        lo[a] = Math.min(lo[a], positions[i + a]);
        hi[a] = Math.max(hi[a], positions[i + a]);
      }
    }
    const diagonal = Math.hypot(...hi.map((x, a) => x - lo[a])) || 1;
    // A flat or empty box gets some thickness, so every cell has a size.
    for (let a = 0; a < 3; a++) {
      if (!(hi[a] - lo[a] > 1e-6 * diagonal)) [lo[a], hi[a]] = [lo[a] - 1e-3 * diagonal, hi[a] + 1e-3 * diagonal];
    }
    const size = hi.map((x, a) => x - lo[a]);
    const cells = Math.min(MAX_CELLS, Math.max(1, nt / PER_CELL));
    const h = Math.cbrt((size[0] * size[1] * size[2]) / cells);
    this.lo = lo;
    this.dims = size.map((s) => Math.max(1, Math.min(1024, Math.ceil(s / h))));
    this.cell = size.map((s, a) => s / this.dims[a]);
    this._fill(nt);
    this.stamp = new Uint32Array(nt);
    this.ray = 0;
  }

  /** The cell index along axis a of the coordinate x (clamped to the grid). */
  _cellOf(x, a) {
    return Math.min(this.dims[a] - 1, Math.max(0, Math.floor((x - this.lo[a]) / this.cell[a])));
  }

  /** Lists each triangle in every cell its bounding box touches (CSR:
   * start, items). */
  _fill(nt) {
    const [nx, ny] = this.dims;
    const n = nx * ny * this.dims[2];
    const start = new Uint32Array(n + 1);
    const boxes = new Int32Array(6 * nt);
    const { positions: P, triangles: T } = this;
    for (let t = 0; t < nt; t++) {
      for (let a = 0; a < 3; a++) {
        const x = [P[3 * T[3 * t] + a], P[3 * T[3 * t + 1] + a], P[3 * T[3 * t + 2] + a]];
        boxes[6 * t + a] = this._cellOf(Math.min(...x), a);
        boxes[6 * t + 3 + a] = this._cellOf(Math.max(...x), a);
      }
    }
    const each = (t, visit) => {
      const b = 6 * t;
      for (let k = boxes[b + 2]; k <= boxes[b + 5]; k++) {
        for (let j = boxes[b + 1]; j <= boxes[b + 4]; j++) {
          for (let i = boxes[b]; i <= boxes[b + 3]; i++) visit((k * ny + j) * nx + i);
        }
      }
    };
    for (let t = 0; t < nt; t++) each(t, (c) => start[c + 1]++);
    for (let c = 0; c < n; c++) start[c + 1] += start[c];
    const items = new Uint32Array(start[n]);
    const fill = start.slice(0, n);
    for (let t = 0; t < nt; t++) each(t, (c) => (items[fill[c]++] = t));
    this.start = start;
    this.items = items;
  }

  /** The segment parameter (0..1) where the segment a + s (b - a) meets
   * triangle t, or Infinity. */
  _hit(t, a, d) {
    const { positions: P, triangles: T } = this;
    const [i, j, k] = [3 * T[3 * t], 3 * T[3 * t + 1], 3 * T[3 * t + 2]];
    const e1 = [P[j] - P[i], P[j + 1] - P[i + 1], P[j + 2] - P[i + 2]];
    const e2 = [P[k] - P[i], P[k + 1] - P[i + 1], P[k + 2] - P[i + 2]];
    const p = [d[1] * e2[2] - d[2] * e2[1], d[2] * e2[0] - d[0] * e2[2], d[0] * e2[1] - d[1] * e2[0]];
    const det = e1[0] * p[0] + e1[1] * p[1] + e1[2] * p[2];
    if (det === 0) return Infinity;
    const inv = 1 / det;
    const s = [a[0] - P[i], a[1] - P[i + 1], a[2] - P[i + 2]];
    const u = (s[0] * p[0] + s[1] * p[1] + s[2] * p[2]) * inv;
    if (u < 0 || u > 1) return Infinity;
    const q = [s[1] * e1[2] - s[2] * e1[1], s[2] * e1[0] - s[0] * e1[2], s[0] * e1[1] - s[1] * e1[0]];
    const v = (d[0] * q[0] + d[1] * q[1] + d[2] * q[2]) * inv;
    if (v < 0 || u + v > 1) return Infinity;
    const at = (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) * inv;
    return at >= 0 ? at : Infinity;
  }

  /**
   * Whether a triangle lies between `from` (the camera) and `to` (a model
   * point): the segment meets one before its last END_SLACK.
   * @param {number[]} from
   * @param {number[]} to
   */
  blocked(from, to) {
    const d = to.map((x, a) => x - from[a]);
    const end = 1 - END_SLACK;
    // The part of the segment inside the grid's box.
    let t0 = 0;
    let t1 = end;
    for (let a = 0; a < 3; a++) {
      const lo = this.lo[a];
      const hi = lo + this.dims[a] * this.cell[a];
      if (d[a] === 0) {
        if (from[a] < lo || from[a] > hi) return false;
        continue;
      }
      let [u, v] = [(lo - from[a]) / d[a], (hi - from[a]) / d[a]];
      if (u > v) [u, v] = [v, u];
      t0 = Math.max(t0, u);
      t1 = Math.min(t1, v);
    }
    if (t0 > t1) return false;
    // Cell by cell along the segment from t0.
    const ray = ++this.ray;
    if (ray === 0xffffffff) {
      this.stamp.fill(0);
      this.ray = 1;
    }
    const cell = [0, 1, 2].map((a) => this._cellOf(from[a] + t0 * d[a], a));
    const step = d.map((x) => (x > 0 ? 1 : x < 0 ? -1 : 0));
    const next = [0, 1, 2].map((a) => {
      if (!step[a]) return Infinity;
      const edge = this.lo[a] + (cell[a] + (step[a] > 0 ? 1 : 0)) * this.cell[a];
      return (edge - from[a]) / d[a];
    });
    const delta = [0, 1, 2].map((a) => (step[a] ? this.cell[a] / Math.abs(d[a]) : Infinity));
    const [nx, ny] = this.dims;
    for (;;) {
      const c = (cell[2] * ny + cell[1]) * nx + cell[0];
      for (let i = this.start[c]; i < this.start[c + 1]; i++) {
        const t = this.items[i];
        if (this.stamp[t] === ray) continue;
        this.stamp[t] = ray;
        if (this._hit(t, from, d) < end) return true;
      }
      const a = next[0] < next[1] ? (next[0] < next[2] ? 0 : 2) : next[1] < next[2] ? 1 : 2;
      if (next[a] > t1) return false;
      cell[a] += step[a];
      if (cell[a] < 0 || cell[a] >= this.dims[a]) return false;
      next[a] += delta[a];
    }
  }
}
