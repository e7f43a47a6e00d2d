// three.js view: one content at a time (a triangle surface colored per
// triangle by quality, or the clipped volume of volume-view.js), orbit
// controls, fit-to-view, a wireframe overlay, highlighted loops, overlays
// that outlive the content (the cut discs), per-vertex colours of the
// surface (the size view), picking a point on the surface, projecting
// model points to the view (the labels and marks drawn over it follow each
// frame: onRender, dimmed when hidden behind the surface: hiddenBehind) and
// zooming to a place.
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';

import { qualityColor } from './colormap.js';
import { Occluder } from './occlusion.js';

export class Viewer {
  /** @param {HTMLElement} container */
  constructor(container) {
    this.container = container;
    this.renderer = new THREE.WebGLRenderer({ antialias: true });
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio, 2));
    this.renderer.setClearColor(0xe9edf1);
    this.renderer.localClippingEnabled = true; // the volume's context surface
    container.prepend(this.renderer.domElement);

    this.scene = new THREE.Scene();
    this.camera = new THREE.PerspectiveCamera(35, 1, 0.01, 1000);
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x667788, 1.6));
    this.light = new THREE.DirectionalLight(0xffffff, 1.4);
    this.scene.add(this.light);

    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.addEventListener('change', () => this.render());

    this.content = null; // a THREE.Object3D
    this.sphere = null; // bounding sphere of the content
    this.wire = null; // the surface's wireframe overlay
    this.loop = null;
    this.solid = null; // the surface's triangles (picking)
    this.raycaster = new THREE.Raycaster();
    this.renderListeners = [];
    new ResizeObserver(() => this.resize()).observe(container);
    this.resize();
  }

  resize() {
    const { clientWidth: w, clientHeight: h } = this.container;
    if (w === 0 || h === 0) return;
    this.renderer.setSize(w, h, false);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.render();
  }

  render() {
    this.light.position.copy(this.camera.position);
    this.renderer.render(this.scene, this.camera);
    for (const listener of this.renderListeners) listener();
  }

  /** Calls `listener` after each frame drawn (the camera may have moved). */
  onRender(listener) {
    this.renderListeners.push(listener);
  }

  /** Shows a surface: positions (3V floats), triangles (3T indices), quality
   * (T); the view is fitted to it unless fit is false. */
  setSurface({ positions, triangles, quality }, { fit = true } = {}) {
    const nt = triangles.length / 3;
    const pos = new Float32Array(9 * nt);
    const col = new Float32Array(9 * nt);
    for (let t = 0; t < nt; t++) {
      for (let c = 0; c < 3; c++) {
        const v = triangles[3 * t + c];
        pos.set(positions.subarray(3 * v, 3 * v + 3), 9 * t + 3 * c);
        qualityColor(quality[t], col, 9 * t + 3 * c);
      }
    }
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(pos, 3));
    geometry.setAttribute('color', new THREE.BufferAttribute(col, 3));
    geometry.computeVertexNormals(); // non-indexed: flat per triangle
    geometry.computeBoundingSphere();
    const solid = new THREE.Mesh(
      geometry,
      new THREE.MeshLambertMaterial({
        vertexColors: true,
        side: THREE.DoubleSide,
        polygonOffset: true,
        polygonOffsetFactor: 1,
        polygonOffsetUnits: 1,
      }),
    );
    const wire = new THREE.Mesh(
      geometry,
      new THREE.MeshBasicMaterial({ color: 0x1d2733, wireframe: true, transparent: true, opacity: 0.35 }),
    );
    wire.visible = this.wireframe ?? false;
    const group = new THREE.Group();
    group.add(solid, wire);
    this.setContent(group, geometry.boundingSphere, { fit, occluder: { positions, triangles } });
    this.wire = wire;
    this.solid = solid;
    this.surface = { triangles, quality };
  }

  /**
   * Colours the shown surface (setSurface) per vertex: `colors` holds 3
   * floats (RGB 0..1) a vertex of its positions; null brings back the
   * quality colours. False when no surface is shown.
   */
  setVertexColors(colors) {
    if (!this.solid || !this.surface) return false;
    const { triangles, quality } = this.surface;
    const attribute = this.solid.geometry.getAttribute('color');
    const col = attribute.array;
    for (let t = 0; t < triangles.length / 3; t++) {
      for (let c = 0; c < 3; c++) {
        const o = 9 * t + 3 * c;
        if (colors) col.set(colors.subarray(3 * triangles[3 * t + c], 3 * triangles[3 * t + c] + 3), o);
        else qualityColor(quality[t], col, o);
      }
    }
    attribute.needsUpdate = true;
    this.render();
    return true;
  }

  /**
   * Replaces the shown content (the previous one is disposed) and fits the
   * view to `sphere` (a THREE.Sphere) unless fit is false; `occluder`
   * ({positions, triangles}) is the surface that hides what lies behind it.
   */
  setContent(object, sphere, { fit = true, occluder = null } = {}) {
    this.clear();
    this.content = object;
    this.sphere = sphere;
    this.occluderSource = occluder;
    this.scene.add(object);
    if (fit) this.fitView();
    else this.render();
  }

  clear() {
    if (this.content) {
      this.scene.remove(this.content);
      this.content.traverse((obj) => {
        obj.geometry?.dispose();
        obj.material?.dispose();
      });
    }
    this.content = this.sphere = this.wire = this.solid = this.surface = null;
    this.occluderSource = this.occluder = null;
    this.highlightLoop(null);
  }

  /** Shows the surface's wireframe (the volume view draws its own edges). */
  setWireframe(on) {
    this.wireframe = on;
    if (this.wire) this.wire.visible = on;
    this.render();
  }

  /**
   * Highlights a closed loop of vertex indices into `positions` (3 floats a
   * vertex), or removes it with null.
   */
  highlightLoop(vertices, positions) {
    if (this.loop) {
      this.scene.remove(this.loop);
      this.loop.geometry.dispose();
      this.loop.material.dispose();
      this.loop = null;
    }
    if (vertices && positions) {
      const pts = new Float32Array(3 * vertices.length);
      vertices.forEach((v, i) => pts.set(positions.subarray(3 * v, 3 * v + 3), 3 * i));
      const geometry = new THREE.BufferGeometry();
      geometry.setAttribute('position', new THREE.BufferAttribute(pts, 3));
      this.loop = new THREE.LineLoop(
        geometry,
        new THREE.LineBasicMaterial({ color: 0xd0104c, depthTest: false }),
      );
      this.loop.renderOrder = 2;
      this.scene.add(this.loop);
    }
    this.render();
  }

  /** Adds an object drawn over any content (kept when the content changes). */
  addOverlay(object) {
    this.scene.add(object);
    this.render();
  }

  /** Removes an overlay added with addOverlay (the caller disposes it). */
  removeOverlay(object) {
    this.scene.remove(object);
    this.render();
  }

  /**
   * The point of the shown surface (setSurface) under the page coordinates
   * (clientX, clientY), as [x, y, z], or null (no surface there, or another
   * content shown).
   */
  pick(clientX, clientY) {
    if (!this.solid) return null;
    const rect = this.renderer.domElement.getBoundingClientRect();
    const ndc = new THREE.Vector2(
      ((clientX - rect.left) / rect.width) * 2 - 1,
      -((clientY - rect.top) / rect.height) * 2 + 1,
    );
    this.raycaster.setFromCamera(ndc, this.camera);
    const [hit] = this.raycaster.intersectObject(this.solid, false);
    return hit ? hit.point.toArray() : null;
  }

  /** The page coordinates of the model point p ([x, y, z]), or null when it
   * is behind the camera. */
  screenPoint(p) {
    const v = new THREE.Vector3(...p).project(this.camera);
    if (v.z > 1) return null;
    const rect = this.renderer.domElement.getBoundingClientRect();
    return [rect.left + ((v.x + 1) / 2) * rect.width, rect.top + ((1 - v.y) / 2) * rect.height];
  }

  /** Whether the model point p ([x, y, z]) is hidden from the camera by the
   * content's surface (its occluder; the grid built at the first ask). */
  hiddenBehind(p) {
    if (!this.occluderSource) return false;
    const { positions, triangles } = this.occluderSource;
    this.occluder ??= new Occluder(positions, triangles);
    return this.occluder.blocked(this.camera.position.toArray(), p);
  }

  /** The position of the model point p ([x, y, z]) in the view, in CSS
   * pixels from the canvas' top left corner, or null when it is behind the
   * camera or outside the view. */
  viewPoint(p) {
    const v = new THREE.Vector3(...p).project(this.camera);
    if (v.z > 1 || Math.abs(v.x) > 1 || Math.abs(v.y) > 1) return null;
    const { clientWidth: w, clientHeight: h } = this.renderer.domElement;
    return [((v.x + 1) / 2) * w, ((1 - v.y) / 2) * h];
  }

  /** Turns the camera to look at the model point p from `radius` times 8
   * away (at least two thirds of the model's radius, so what is around it
   * is seen too), the viewing direction kept. */
  focusOn(p, radius = 0) {
    const target = new THREE.Vector3(...p);
    const offset = this.camera.position.clone().sub(this.controls.target);
    const model = this.sphere?.radius ?? 1;
    const distance = Math.max(8 * radius, (2 * model) / 3);
    offset.setLength(distance);
    this.controls.target.copy(target);
    this.camera.position.copy(target).add(offset);
    this.camera.near = Math.min(this.camera.near, distance / 100);
    this.camera.updateProjectionMatrix();
    this.controls.update();
    this.render();
  }

  /** Orbits the camera around the target: `azimuth` about the up axis,
   * `polar` towards it (radians; the pole is not crossed). */
  orbit(azimuth, polar) {
    const up = new THREE.Quaternion().setFromUnitVectors(this.camera.up, new THREE.Vector3(0, 1, 0));
    const offset = this.camera.position.clone().sub(this.controls.target).applyQuaternion(up);
    const s = new THREE.Spherical().setFromVector3(offset);
    s.theta -= azimuth;
    s.phi = Math.min(Math.PI - 0.01, Math.max(0.01, s.phi + polar));
    offset.setFromSpherical(s).applyQuaternion(up.invert());
    this.camera.position.copy(this.controls.target).add(offset);
    this.camera.lookAt(this.controls.target);
    this.controls.update();
    this.render();
  }

  /** Moves the camera `factor` times its distance from the target (< 1: in). */
  zoom(factor) {
    const offset = this.camera.position.clone().sub(this.controls.target).multiplyScalar(factor);
    this.camera.position.copy(this.controls.target).add(offset);
    this.controls.update();
    this.render();
  }

  fitView() {
    if (!this.sphere) return;
    const sphere = this.sphere;
    const distance = sphere.radius / Math.sin(THREE.MathUtils.degToRad(this.camera.fov / 2));
    const direction = new THREE.Vector3(0.6, -0.9, 0.5).normalize();
    this.camera.near = distance / 100;
    this.camera.far = distance * 10;
    this.camera.up.set(0, 0, 1);
    this.camera.position.copy(sphere.center).addScaledVector(direction, distance * 1.05);
    this.camera.updateProjectionMatrix();
    this.controls.target.copy(sphere.center);
    this.controls.update();
    this.render();
  }
}
