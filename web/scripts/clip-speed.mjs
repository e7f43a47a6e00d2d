// Speed of the clipped volume view on a generated grid of tetrahedra:
//   node web/scripts/clip-speed.mjs [N] [--shuffle]   (6 N^3 tets; N = 55: ~1M)
// --shuffle numbers vertices and tetrahedra randomly (no memory locality).
// Prints the one-off costs (face adjacency, centroids) and the time of one
// slider move (clipBoundary at a new plane position), median of 21 moves.
import { ClipBuffers, clipBoundary, faceAdjacency, tetCentroids } from '../src/clip.js';
import { kuhnGrid } from '../test/kuhn-grid.js';

const n = Number(process.argv[2] ?? 55);
let t0 = performance.now();
const mesh = kuhnGrid(n, { boundary: false });
const nt = mesh.tets.length / 4;
if (process.argv.includes('--shuffle')) shuffle(mesh);
console.log(`${nt.toLocaleString('en')} tetrahedra, ${mesh.vertexCount.toLocaleString('en')} vertices (grid ${(performance.now() - t0).toFixed(0)} ms)`);

t0 = performance.now();
const across = faceAdjacency(mesh.tets, mesh.vertexCount);
console.log(`face adjacency: ${(performance.now() - t0).toFixed(0)} ms`);
t0 = performance.now();
const centroid = tetCentroids(mesh.positions, mesh.tets, 2);
console.log(`centroids along one axis: ${(performance.now() - t0).toFixed(0)} ms`);

const tagColors = new Uint8Array([200, 200, 200]);
const tetColors = new Uint8Array(3 * nt).fill(128);
const out = new ClipBuffers();
for (const colors of [null, tetColors]) {
  const times = [];
  for (let i = 0; i <= 20; i++) {
    const value = n * (0.2 + (0.6 * i) / 20);
    t0 = performance.now();
    clipBoundary(mesh, across, centroid, { value, tagColors, cutColor: [1, 2, 3], tetColors: colors }, out);
    times.push(performance.now() - t0);
  }
  times.sort((a, b) => a - b);
  console.log(
    `slider move (${colors ? 'gamma_t' : 'group'} colors): median ${times[10].toFixed(1)} ms, max ${times[20].toFixed(1)} ms, last ${out.count.toLocaleString('en')} triangles (${out.cut.toLocaleString('en')} cut)`,
  );
}

/** Random vertex numbering and tetrahedron order (seeded). */
function shuffle({ positions, tets, vertexCount }) {
  let seed = 12345;
  const random = (k) => ((seed = (seed * 1103515245 + 12345) >>> 0) % k);
  const permutation = (k) => {
    const p = Uint32Array.from({ length: k }, (_, i) => i);
    for (let i = k - 1; i > 0; i--) {
      const j = random(i + 1);
      [p[i], p[j]] = [p[j], p[i]];
    }
    return p;
  };
  const pv = permutation(vertexCount);
  const moved = new Float32Array(positions.length);
  for (let v = 0; v < vertexCount; v++) moved.set(positions.subarray(3 * v, 3 * v + 3), 3 * pv[v]);
  positions.set(moved);
  const pt = permutation(tets.length / 4);
  const old = tets.slice();
  for (let t = 0; t < pt.length; t++) {
    for (let k = 0; k < 4; k++) tets[4 * pt[t] + k] = pv[old[4 * t + k]];
  }
}
