// The pictures of the methods report, drawn by the page's own three.js view
// (the viewer and its volume view): the wall mesh with its edges, a cut
// through the volume, and a close-up of the boundary layer where that cut
// meets the wall. Each picture is drawn at a fixed size and copied at once
// (canvas.toBlob takes its copy when called, right after the frame is drawn,
// so the renderer needs no preserveDrawingBuffer); the whole capture runs in
// one task and puts the view back before returning, so the user never sees
// the pictures being taken and finds the view as it was.
import * as THREE from 'three';

import { PARTS } from './groups.js';

/** The pictures' size in pixels (3:2, sharp in a printed A4 page). */
export const REPORT_VIEW_SIZE = [1200, 800];

const AXES = 'xyz';
const count = (n) => n.toLocaleString('en');
const short = (x) => String(Number(x.toPrecision(3)));

/** What restoreView() needs to put the camera and the renderer back. */
function saveView(viewer) {
  const { camera, controls, renderer } = viewer;
  return {
    position: camera.position.clone(),
    up: camera.up.clone(),
    near: camera.near,
    far: camera.far,
    aspect: camera.aspect,
    target: controls.target.clone(),
    size: renderer.getSize(new THREE.Vector2()),
    ratio: renderer.getPixelRatio(),
    wireframe: viewer.wireframe ?? false,
  };
}

function restoreView(viewer, saved) {
  const { camera, controls, renderer } = viewer;
  renderer.setPixelRatio(saved.ratio);
  renderer.setSize(saved.size.x, saved.size.y, false);
  camera.position.copy(saved.position);
  camera.up.copy(saved.up);
  Object.assign(camera, { near: saved.near, far: saved.far, aspect: saved.aspect });
  camera.updateProjectionMatrix();
  controls.target.copy(saved.target);
  controls.update();
  viewer.render();
}

/** The coordinate axis (a unit vector) most across `v`. */
function axisAcross(v) {
  const a = [Math.abs(v.x), Math.abs(v.y), Math.abs(v.z)];
  return new THREE.Vector3().setComponent(a.indexOf(Math.min(...a)), 1);
}

/** Points the camera at `target` from `direction` (a unit vector), `distance` away. */
function aim(viewer, target, direction, distance, up) {
  const { camera } = viewer;
  // Up along the line of sight has no meaning: the axis most across it will do.
  camera.up.copy(Math.abs(up.dot(direction)) > 0.99 ? axisAcross(direction) : up);
  camera.position.copy(target).addScaledVector(direction, distance);
  camera.near = distance / 100;
  camera.far = distance * 10;
  camera.updateProjectionMatrix();
  camera.lookAt(target);
}

/** The distance at which the sphere fills the view's height. */
function fitDistance(viewer, sphere) {
  return (1.05 * sphere.radius) / Math.sin(THREE.MathUtils.degToRad(viewer.camera.fov / 2));
}

/** Draws a frame and takes its copy (a Promise of PNG bytes, or null). */
function snap(viewer) {
  viewer.render();
  return new Promise((resolve) => viewer.renderer.domElement.toBlob(resolve, 'image/png')).then(async (blob) =>
    blob ? new Uint8Array(await blob.arrayBuffer()) : null,
  );
}

/**
 * Where the plane (coordinate `value` along axis `k`) crosses the wall: of
 * the wall's triangles cut by the plane, the crossing point farthest from
 * the model's centre (on the outside of a vessel, away from a crotch), with
 * the mean edge length of its triangle (the local mesh size h). Null when
 * the plane misses the wall.
 */
function wallCrossing(volume, k, value, center) {
  const { positions: p, triangles, triangleTag, surfaceNames } = volume;
  const wall = surfaceNames.indexOf('wall');
  let best = null;
  const q = new THREE.Vector3();
  const at = (v) => new THREE.Vector3(p[3 * v], p[3 * v + 1], p[3 * v + 2]);
  for (let t = 0; t < triangleTag.length; t++) {
    if (wall >= 0 && triangleTag[t] !== wall) continue;
    const d = [0, 1, 2].map((i) => p[3 * triangles[3 * t + i] + k] - value);
    if (Math.min(...d) > 0 || Math.max(...d) < 0) continue;
    const c = [0, 1, 2].map((i) => at(triangles[3 * t + i]));
    for (let i = 0; i < 3; i++) {
      const j = (i + 1) % 3;
      if ((d[i] < 0) === (d[j] < 0) || d[i] === d[j]) continue;
      q.lerpVectors(c[i], c[j], d[i] / (d[i] - d[j]));
      const r = q.distanceToSquared(center);
      if (best && r <= best.r) continue;
      const h = (c[0].distanceTo(c[1]) + c[1].distanceTo(c[2]) + c[2].distanceTo(c[0])) / 3;
      best = { point: q.clone(), h, r };
    }
  }
  return best;
}

/**
 * Around the wall point `q` on the plane (normal `n`), of the kept
 * tetrahedra within 2 h: `inside`, the direction in the plane towards the
 * inside of the vessel (towards their mean centroid), and `layer`, the
 * boundary layer's thickness there (the distance in the plane to the
 * nearest vertex of a core tetrahedron; 0 without layers).
 */
function around(volume, q, n, h, keep) {
  const { positions: p, tets, tetPart } = volume;
  const sum = new THREE.Vector3();
  const c = new THREE.Vector3();
  const d = new THREE.Vector3();
  let found = 0;
  let nearest = Infinity;
  for (let i = 0, t = 0; i < tets.length; i += 4, t++) {
    let [x, y, z] = [0, 0, 0];
    for (let j = 0; j < 4; j++) {
      const v = 3 * tets[i + j];
      x += p[v];
      y += p[v + 1];
      z += p[v + 2];
    }
    c.set(x / 4, y / 4, z / 4);
    if (c.distanceToSquared(q) > 4 * h * h || !keep(c)) continue;
    sum.add(c);
    found++;
    if (!tetPart || tetPart[t] !== 0) continue;
    for (let j = 0; j < 4; j++) {
      const v = 3 * tets[i + j];
      d.set(p[v], p[v + 1], p[v + 2]).sub(q);
      d.addScaledVector(n, -d.dot(n));
      nearest = Math.min(nearest, d.length());
    }
  }
  const inside = found ? sum.divideScalar(found).sub(q) : new THREE.Vector3();
  inside.addScaledVector(n, -inside.dot(n));
  const layered = tetPart?.some((part) => part === 1);
  return {
    inside: inside.lengthSq() > 0 ? inside.normalize() : axisAcross(n),
    layer: layered && Number.isFinite(nearest) ? nearest : 0,
  };
}

/** The wall's quality as written (after boundary recovery), as results.js shows it. */
function wallQuality(out) {
  return out.volume?.surfaces?.find((s) => s.name === 'wall')?.quality ?? out.quality;
}

/**
 * Draws the report's pictures in `viewer` and puts the view back.
 * @param {object} options
 * @param {import('./viewer.js').Viewer} options.viewer
 * @param {import('./volume-view.js').VolumeView} [options.volumeView] the
 *   viewer's volume view (none: the wall only)
 * @param {object} options.result the mesh result (its volume with the prisms
 *   split, as the volume view takes it)
 * @param {() => void} options.restore shows again what the viewer showed
 *   (called before the camera is put back)
 * @returns {Promise<{title: string, alt: string, png: Uint8Array}[]>}
 */
export async function captureReportViews({ viewer, volumeView, result, restore }) {
  const out = result.report.output;
  const unit = out.unit ?? '';
  const saved = saveView(viewer);
  const savedOptions = volumeView && { ...volumeView.options };
  // Overlays (cut discs, measurements, marks of places) stay out of the pictures.
  const hidden = viewer.scene.children.filter((o) => !o.isLight && o.visible);
  const shots = [];
  try {
    for (const o of hidden) o.visible = false;
    const [w, h] = REPORT_VIEW_SIZE;
    viewer.renderer.setPixelRatio(1);
    viewer.renderer.setSize(w, h, false);
    viewer.camera.aspect = w / h;
    // The user's viewing direction, fitted to the whole model.
    const direction = saved.position.clone().sub(saved.target).normalize();

    viewer.setSurface(result.surface, { fit: false });
    viewer.setWireframe(true);
    aim(viewer, viewer.sphere.center, direction, fitDistance(viewer, viewer.sphere), saved.up);
    const q = wallQuality(out);
    shots.push({
      title: 'Wall mesh',
      alt:
        `Wall mesh, ${count(out.triangles)} triangles with their edges, coloured by quality γk ` +
        `(min ${q.min.toFixed(3)}, mean ${q.mean.toFixed(3)}; red 0 to blue 1).`,
      png: snap(viewer),
    });

    const volume = result.volume;
    if (volumeView && volume) shots.push(...cutViews(viewer, volumeView, result, { direction, up: saved.up, unit }));
  } finally {
    if (volumeView) Object.assign(volumeView.options, savedOptions);
    for (const o of hidden) o.visible = true;
    viewer.wireframe = saved.wireframe;
    restore();
    restoreView(viewer, saved);
  }
  const pictures = await Promise.all(shots.map(async (s) => ({ ...s, png: await s.png })));
  return pictures.filter((s) => s.png);
}

/** The cut through the volume (the volume view's plane, coloured by part)
 * and the close-up of the boundary layer on it. */
function cutViews(viewer, volumeView, result, { direction, up, unit }) {
  const { volume } = result;
  Object.assign(volumeView.options, { color: 'part', edges: true, boundary: true });
  volumeView.show(volume);
  const { axis: k, value } = volumeView.planeValue();
  const flip = volumeView.options.flip;
  // The camera on the removed side, looking at the cut at 35° to its normal.
  const n = new THREE.Vector3().setComponent(k, flip ? -1 : 1);
  const across = direction.clone().addScaledVector(n, -direction.dot(n));
  if (across.lengthSq() < 1e-6) across.copy(axisAcross(n));
  across.normalize();
  const oblique = n.clone().multiplyScalar(Math.cos(0.61)).addScaledVector(across, Math.sin(0.61)).normalize();
  // Fitted to what is kept (the cut large in the picture), the removed part
  // transparent around it.
  const { cut, cutByPart, count: drawn, positions } = volumeView.buffers;
  const kept = new THREE.Box3().setFromArray(positions.subarray(0, 9 * drawn)).getBoundingSphere(new THREE.Sphere());
  const fit = drawn ? kept : viewer.sphere;
  aim(viewer, fit.center, oblique, fitDistance(viewer, fit), up);
  const parts = PARTS.flatMap(({ name }, i) => (cutByPart[i] ? [`${name} ${count(cutByPart[i])}`] : []));
  const tets = volume.tets.length / 4;
  const plane = `${AXES[k]} = ${short(value)} ${unit}`.trim();
  const shots = [
    {
      title: 'Cut through the volume',
      alt:
        `The volume mesh cut by the plane ${plane}: ${count(cut)} cut faces of the ${count(tets)} tetrahedra ` +
        `(${parts.join(', ')}), the core in red, the boundary layer in blue, the wall transparent.`,
      png: snap(viewer),
    },
  ];

  const crossing = wallCrossing(volume, k, value, viewer.sphere.center);
  if (!crossing) return shots;
  // Looking straight at the cut, the wall at the bottom, the vessel's inside
  // above it: the layer a quarter of the picture's height (at most 2.5 wall
  // edges high, at least one), so that every layer shows.
  const keep = (c) => (flip ? c.getComponent(k) >= value : c.getComponent(k) <= value);
  const { inside, layer: thickness } = around(volume, crossing.point, n, crossing.h, keep);
  const height = Math.min(2.5 * crossing.h, Math.max(crossing.h, 4 * thickness));
  const target = crossing.point.clone().addScaledVector(inside, 0.3 * height);
  Object.assign(volumeView.options, { boundary: false });
  volumeView.update();
  aim(viewer, target, n, height / 2 / Math.tan(THREE.MathUtils.degToRad(viewer.camera.fov / 2)), inside);
  const layer = result.report.output.volume?.boundary_layer;
  const width = (height * REPORT_VIEW_SIZE[0]) / REPORT_VIEW_SIZE[1];
  const thick = thickness > 0 ? `, about ${short(thickness)} ${unit} thick` : '';
  const layers = layer ? `${layer.layers} boundary layers (blue${thick})` : 'no boundary layer';
  shots.push({
    title: 'Boundary layer, close-up',
    alt:
      `Close-up of the cut ${plane} where it meets the wall (at the bottom): ${layers} ` +
      `between the wall and the core tetrahedra (red); the picture is ${short(width)} ${unit} wide.`,
    png: snap(viewer),
  });
  return shots;
}
