// The volume view: the tetrahedra (core, boundary layer, vessel wall) cut by
// an axis-aligned clipping plane as Gmsh draws them (clip.js: tets kept by
// the side of their centroid, the faces of the kept set not shared by two
// kept tets), shaded, with thin edges, colored by gamma_t, by part (core,
// boundary layer, vessel wall) or by group (the boundary by surface group,
// the cut by volume group); the boundary on the removed side is drawn
// transparent for context (or hidden).
import * as THREE from 'three';

import { ClipBuffers, clipBoundary, tetCentroids } from './clip.js';
import { qualityColor } from './colormap.js';
import { groupColor, groupColors, PARTS } from './groups.js';

const AXES = { x: 0, y: 1, z: 2 };
const byte = (x) => Math.round(255 * x);
const GREY = [150, 150, 150];
const prepared = new WeakMap(); // volume -> what every plane position reuses

/** 3 bytes per tet: the color of its entry of `table` (RGB 0..1 each). */
function colorsByIndex(index, table) {
  const bytes = table.map((rgb) => rgb.map(byte));
  const out = new Uint8Array(3 * index.length);
  for (let t = 0; t < index.length; t++) {
    const c = bytes[index[t]] ?? GREY;
    out[3 * t] = c[0];
    out[3 * t + 1] = c[1];
    out[3 * t + 2] = c[2];
  }
  return out;
}

/** Adjacency, colors and bounds of a volume, computed once. */
function prepare(volume) {
  let data = prepared.get(volume);
  if (data) return data;
  const { tets, tetQuality, positions, surfaceNames } = volume;
  const nt = tets.length / 4;
  const tetPart = volume.tetPart ?? new Uint8Array(nt);
  const regionNames = volume.regionNames ?? ['lumen'];
  const { across } = volume; // the core's, for the tets and the prisms' split (clip.js)
  // gamma_t colors through a 256-entry table of the colormap.
  const table = new Uint8Array(3 * 256);
  const rgb = [0, 0, 0];
  for (let i = 0; i < 256; i++) {
    qualityColor(i / 255, rgb);
    for (let k = 0; k < 3; k++) table[3 * i + k] = byte(rgb[k]);
  }
  const tetColors = new Uint8Array(3 * nt);
  for (let t = 0; t < nt; t++) {
    const i = 3 * Math.round(255 * Math.min(1, Math.max(0, tetQuality[t])));
    tetColors[3 * t] = table[i];
    tetColors[3 * t + 1] = table[i + 1];
    tetColors[3 * t + 2] = table[i + 2];
  }
  // One color per surface tag, then one for faces without a tag.
  const tagColors = Uint8Array.from(groupColors([...surfaceNames, '']).flatMap((c) => c.map(byte)));
  const box = new THREE.Box3().setFromArray(positions);
  data = {
    across,
    tetPart,
    tetColors,
    partColors: colorsByIndex(tetPart, PARTS.map((p) => p.color)),
    regionColors: colorsByIndex(volume.tetRegion ?? new Int32Array(nt), groupColors(regionNames)),
    tagColors,
    cutColor: groupColor('lumen').map(byte),
    sphere: box.getBoundingSphere(new THREE.Sphere()),
    centroids: [null, null, null], // per axis, when first asked
    ranges: [null, null, null],
  };
  prepared.set(volume, data);
  return data;
}

/** The wall and caps as one non-indexed geometry colored by group. */
function boundaryGeometry({ positions, triangles, triangleTag, surfaceNames }) {
  const nb = triangleTag.length;
  const pos = new Float32Array(9 * nb);
  const col = new Uint8Array(9 * nb);
  const colors = groupColors(surfaceNames).map((c) => c.map(byte));
  for (let t = 0; t < nb; t++) {
    const c = colors[triangleTag[t]] ?? [150, 150, 150];
    for (let k = 0; k < 3; k++) {
      const v = triangles[3 * t + k];
      pos.set(positions.subarray(3 * v, 3 * v + 3), 9 * t + 3 * k);
      col.set(c, 9 * t + 3 * k);
    }
  }
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(pos, 3));
  geometry.setAttribute('color', new THREE.BufferAttribute(col, 3, true));
  return geometry;
}

export class VolumeView {
  /**
   * @param {import('./viewer.js').Viewer} viewer
   * @param {(info: {triangles: number, cut: number, cutByPart: number[],
   *   ms: number}) => void} [onDraw] called after each redraw (cutByPart: the
   *   cut faces of the core, the boundary layer and the vessel wall)
   */
  constructor(viewer, onDraw) {
    this.viewer = viewer;
    this.onDraw = onDraw;
    this.options = {
      axis: 'z',
      position: 0.5,
      flip: false,
      color: 'part',
      boundary: true,
      edges: true,
    };
    this.volume = null;
    this.group = null;
    this.frame = 0;
  }

  /** Whether the viewer shows this view now. */
  get active() {
    return this.group !== null && this.viewer.content === this.group;
  }

  /** Shows `volume` (a mesh result's volume) in the viewer, fitted. */
  show(volume) {
    this.volume = volume;
    this.data = prepare(volume);
    this.buffers = new ClipBuffers(Math.ceil(volume.triangleTag.length * 1.2) + 1024);
    this.geometry = null;
    this.solid = new THREE.Mesh(
      new THREE.BufferGeometry(),
      new THREE.MeshLambertMaterial({
        vertexColors: true,
        flatShading: true,
        side: THREE.DoubleSide,
        polygonOffset: true,
        polygonOffsetFactor: 1,
        polygonOffsetUnits: 1,
      }),
    );
    this.edges = new THREE.Mesh(
      this.solid.geometry,
      new THREE.MeshBasicMaterial({ color: 0x1d2733, wireframe: true, transparent: true, opacity: 0.3 }),
    );
    this.plane = new THREE.Plane();
    this.context = new THREE.Mesh(
      boundaryGeometry(volume),
      new THREE.MeshLambertMaterial({
        vertexColors: true,
        side: THREE.DoubleSide,
        transparent: true,
        opacity: 0.22,
        depthWrite: false,
        clippingPlanes: [this.plane],
      }),
    );
    this.context.renderOrder = 1;
    this.group = new THREE.Group();
    this.group.add(this.solid, this.edges, this.context);
    // The wall and caps hide the labels behind them.
    const occluder = { positions: volume.positions, triangles: volume.triangles };
    this.viewer.setContent(this.group, this.data.sphere, { occluder });
    this.update();
  }

  /** Changes options (axis 'x'|'y'|'z', position 0..1, flip, color
   * 'quality'|'part'|'group', boundary, edges); redraws at the next frame. */
  set(options) {
    Object.assign(this.options, options);
    if (this.active && !this.frame) {
      this.frame = requestAnimationFrame(() => {
        this.frame = 0;
        if (this.active) this.update();
      });
    }
  }

  /**
   * The `flip` that keeps the side away from the camera along `axis`, so
   * that the cut faces the viewer.
   */
  flipFacingCamera(axis) {
    const k = AXES[axis];
    const center = this.data ? this.data.sphere.center.getComponent(k) : 0;
    return this.viewer.camera.position.getComponent(k) < center;
  }

  /**
   * Moves the plane through the model point `point` (a place in the mesh:
   * the worst tetrahedron), across the axis the camera looks along most,
   * keeping the side away from the camera, so that the place is on the cut
   * facing the viewer (not in the removed half). Returns the options set
   * {axis, position, flip} (the panel's controls follow them).
   */
  clipThrough(point) {
    const camera = this.viewer.camera.position.toArray();
    const away = camera.map((x, k) => x - point[k]);
    const k = [0, 1, 2].reduce((a, b) => (Math.abs(away[b]) > Math.abs(away[a]) ? b : a));
    const axis = 'xyz'[k];
    const flip = away[k] < 0; // the camera below: keep what is above
    this.options.axis = axis;
    this.planeValue();
    const [lo, hi] = this.data.ranges[k];
    // A hair past the point, so that its element is kept.
    const value = point[k] + (flip ? -1 : 1) * 1e-4 * (hi - lo);
    const position = hi > lo ? Math.min(1, Math.max(0, (value - lo) / (hi - lo))) : 0.5;
    this.set({ axis, flip, position });
    return { axis, position, flip };
  }

  /** The plane's coordinate along the axis, and the axis index. */
  planeValue() {
    const axis = AXES[this.options.axis];
    const d = this.data;
    if (!d.centroids[axis]) {
      const c = tetCentroids(this.volume.positions, this.volume.tets, axis);
      let lo = Infinity;
      let hi = -Infinity;
      for (let t = 0; t < c.length; t++) {
        if (c[t] < lo) lo = c[t];
        if (c[t] > hi) hi = c[t];
      }
      d.centroids[axis] = c;
      d.ranges[axis] = [lo, hi];
    }
    const [lo, hi] = d.ranges[axis];
    return { axis, value: lo + (hi - lo) * this.options.position };
  }

  /** Recomputes the clipped boundary and redraws. */
  update() {
    const start = performance.now();
    const { flip, color } = this.options;
    const { axis, value } = this.planeValue();
    const d = this.data;
    const b = clipBoundary(
      this.volume,
      d.across,
      d.centroids[axis],
      {
        value,
        flip,
        tetColors: { quality: d.tetColors, part: d.partColors }[color] ?? null,
        tagColors: d.tagColors,
        cutColor: d.cutColor,
        cutTetColors: d.regionColors,
        tetPart: d.tetPart,
      },
      this.buffers,
    );
    if (b.grown || !this.geometry) {
      const geometry = new THREE.BufferGeometry();
      const position = new THREE.BufferAttribute(b.positions, 3).setUsage(THREE.DynamicDrawUsage);
      const colors = new THREE.BufferAttribute(b.colors, 3, true).setUsage(THREE.DynamicDrawUsage);
      geometry.setAttribute('position', position);
      geometry.setAttribute('color', colors);
      geometry.boundingSphere = d.sphere.clone(); // the buffers' tails are stale
      this.solid.geometry.dispose();
      this.solid.geometry = this.edges.geometry = this.geometry = geometry;
    } else {
      for (const attribute of Object.values(this.geometry.attributes)) {
        attribute.clearUpdateRanges();
        attribute.addUpdateRange(0, 9 * b.count);
        attribute.needsUpdate = true;
      }
    }
    this.geometry.setDrawRange(0, 3 * b.count);
    // The context surface shows where tets were removed.
    const normal = new THREE.Vector3().setComponent(axis, flip ? -1 : 1);
    this.plane.set(normal, flip ? value : -value);
    this.context.visible = this.options.boundary;
    this.edges.visible = this.options.edges;
    this.viewer.render();
    this.onDraw?.({
      triangles: b.count,
      cut: b.cut,
      cutByPart: [...b.cutByPart],
      ms: performance.now() - start,
    });
  }

  /** Stops pending redraws (the viewer shows something else). */
  hide() {
    if (this.frame) cancelAnimationFrame(this.frame);
    this.frame = 0;
    this.group = null;
  }
}
