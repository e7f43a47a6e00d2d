// The hard inputs of e2e/hard-files.spec.js, generated in the test (no
// real data): each stands for a defect users' files have (README of
// ../shared/data/vascular-hard). Made from the JS API's phantoms (damaged
// ends, crossing vessels: the core's own), or from them and voxels
// (tree.js) where the core has none of the kind.
import { nodeApi } from './helpers.js';
import { stlOf, treeStl, voxelStl } from './tree.js';

/** Whether p is within `r` of the segment a-b (a capsule: rounded ends). */
function inCapsule(p, a, b, r) {
  const d = b.map((x, k) => x - a[k]);
  const v = p.map((x, k) => x - a[k]);
  const t = Math.max(0, Math.min(1, (v[0] * d[0] + v[1] * d[1] + v[2] * d[2]) / (d[0] ** 2 + d[1] ** 2 + d[2] ** 2)));
  return Math.hypot(...v.map((x, k) => x - t * d[k])) <= r;
}

/**
 * A closed bifurcation whose widest vessel is a short trunk (radius 1,
 * 1.6 long to its rounded end, at z = -1.6) under two long branches
 * (radius 0.55, ends at z = 6.5): the trunk's end is too short for a
 * vessel end to be found there, yet it is the inlet.
 * @returns {{stl: Buffer, trunkTip: number[]}}
 */
export function shortTrunkClosed() {
  const tubes = [
    [[0, 0, -0.6], [0, 0, 1], 1],
    [[0, 0, 1], [3.2, 0, 6.5], 0.55],
    [[0, 0, 1], [-3.2, 0, 6.5], 0.55],
  ];
  const stl = voxelStl((p) => tubes.some(([a, b, r]) => inCapsule(p, a, b, r)), {
    min: [-4.5, -1.5, -2.5],
    size: [9, 3, 10],
    voxel: 0.1,
  });
  return { stl, trunkTip: [0, 0, -1.6] };
}

/**
 * A tube (radius 1 along z) closed by domed caps, as a capping tool makes
 * them: each end a fan of triangles around one apex lifted `lift` (0.05) of
 * the end's diameter off its plane, no other inner vertex, no labels.
 */
export async function domedCapsTube(lift = 0.05) {
  const vm = await nodeApi();
  const tube = vm.makePhantom({ kind: 'tube', voxel: 0.12 }).stl;
  const { analysis, surface } = vm.analyze(tube, {});
  const p = (v) => [0, 1, 2].map((a) => surface.positions[3 * v + a]);
  const triangles = [];
  for (let t = 0; t < surface.triangles.length; t += 3) triangles.push([0, 1, 2].map((c) => p(surface.triangles[t + c])));
  for (const o of analysis.openings) {
    const apex = o.centroid.map((x, a) => x + o.normal[a] * lift * 2 * o.radius);
    const rim = o.vertices;
    // The rim runs with the wall on its left: the fan turns the other way.
    for (let i = 0; i < rim.length; i++) triangles.push([p(rim[(i + 1) % rim.length]), p(rim[i]), apex]);
  }
  return stlOf(triangles, 'vesselmesh e2e domed caps');
}

/** A bifurcation whose every opening is damaged as an image border leaves
 * it (folded rim triangles, a flap through the wall, tiny loops, a twist
 * that makes the surface non-orientable): the core's phantom. */
export async function damagedEnds() {
  return Buffer.from((await nodeApi()).makePhantom({ kind: 'bifurcation', voxel: 0.12, damagedEnds: true }).stl);
}

/** Two vessels that touch and pass into each other, each its own closed
 * shell but for its two open ends: the surface crosses itself where they
 * meet (the core's phantom). */
export async function crossingVessels() {
  return Buffer.from((await nodeApi()).makePhantom({ kind: 'crossing' }).stl);
}

/** A bifurcation in centimetres (the parent's radius 1: 1 cm). */
export async function centimetreBifurcation() {
  // An aorta and its iliacs in cm (radii 0.6-1): cm is likely, mm possible.
  return Buffer.from((await nodeApi()).makePhantom({ kind: 'bifurcation', voxel: 0.12 }).stl);
}

/** A vessel tree with 20 open ends: a trunk and 18 side branches around it. */
export function twentyOpenings() {
  return treeStl(0.125, { spiral: 18 });
}

/** A SimVascular-like model: a capped tube with 20 tiny capped branches,
 * each cap 6 triangles, 186 labelled faces (ModelFaceID), as a VTP (the
 * core's outlets phantom). */
export async function labelledOutlets() {
  return Buffer.from((await nodeApi()).makePhantom({ kind: 'outlets' }).vtp);
}
