// three.js view of a triangle surface colored per triangle by quality, with
// orbit controls, fit-to-view, a wireframe overlay and highlighted loops.
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';

import { qualityColor } from './colormap.js';

export class Viewer {
  /** @param {HTMLElement} container */
  constructor(container) {
    this.container = container;
    this.renderer = new THREE.WebGLRenderer({ antialias: true });
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio, 2));
    this.renderer.setClearColor(0xe9edf1);
    container.prepend(this.renderer.domElement);

    this.scene = new THREE.Scene();
    this.camera = new THREE.PerspectiveCamera(35, 1, 0.01, 1000);
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x667788, 1.6));
    this.light = new THREE.DirectionalLight(0xffffff, 1.4);
    this.scene.add(this.light);

    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.addEventListener('change', () => this.render());

    this.solid = null;
    this.wire = null;
    this.loop = null;
    this.positions = null;
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
  }

  /** Shows a surface: positions (3V floats), triangles (3T indices), quality (T). */
  setSurface({ positions, triangles, quality }) {
    this.clear();
    this.positions = positions;
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
    this.solid = new THREE.Mesh(
      geometry,
      new THREE.MeshLambertMaterial({
        vertexColors: true,
        side: THREE.DoubleSide,
        polygonOffset: true,
        polygonOffsetFactor: 1,
        polygonOffsetUnits: 1,
      }),
    );
    this.wire = new THREE.Mesh(
      geometry,
      new THREE.MeshBasicMaterial({ color: 0x1d2733, wireframe: true, transparent: true, opacity: 0.35 }),
    );
    this.wire.visible = this.wireframe ?? false;
    this.scene.add(this.solid, this.wire);
    this.fitView();
  }

  clear() {
    for (const obj of [this.solid, this.wire, this.loop]) {
      if (!obj) continue;
      this.scene.remove(obj);
      obj.material.dispose();
    }
    this.solid?.geometry.dispose();
    this.loop?.geometry.dispose();
    this.solid = this.wire = this.loop = null;
    this.positions = null;
    this.render();
  }

  setWireframe(on) {
    this.wireframe = on;
    if (this.wire) this.wire.visible = on;
    this.render();
  }

  /** Highlights a closed loop of vertex indices (or removes it with null). */
  highlightLoop(vertices) {
    if (this.loop) {
      this.scene.remove(this.loop);
      this.loop.geometry.dispose();
      this.loop.material.dispose();
      this.loop = null;
    }
    if (vertices && this.positions) {
      const pts = new Float32Array(3 * vertices.length);
      vertices.forEach((v, i) => pts.set(this.positions.subarray(3 * v, 3 * v + 3), 3 * i));
      const geometry = new THREE.BufferGeometry();
      geometry.setAttribute('position', new THREE.BufferAttribute(pts, 3));
      this.loop = new THREE.LineLoop(
        geometry,
        new THREE.LineBasicMaterial({ color: 0xd0104c, depthTest: false }),
      );
      this.loop.renderOrder = 1;
      this.scene.add(this.loop);
    }
    this.render();
  }

  fitView() {
    if (!this.solid) return;
    const sphere = this.solid.geometry.boundingSphere;
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
