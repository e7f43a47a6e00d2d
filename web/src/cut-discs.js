// The cuts of the Prepare step drawn on the surface: one translucent disc a
// cut, in its plane, 1.3 times the vessel's radius there (so it shows
// around the vessel), with its outline, a short stick along the normal (the
// side the cut removes) and its number while it is not made yet (once
// made, its opening's label numbers it: one number a place). The selected
// cut is drawn stronger, with its number.
import * as THREE from 'three';

import { disposeOverlay } from './overlay.js';

const DISC_SCALE = 1.3;
const COLOR = 0x1f6fb2;
const SELECTED = 0xd0104c;

/** A sprite with the number `text`, `size` model units high. */
function label(text, size, color) {
  const canvas = document.createElement('canvas');
  canvas.width = canvas.height = 64;
  const g = canvas.getContext('2d');
  g.fillStyle = 'rgba(255, 255, 255, 0.9)';
  g.beginPath();
  g.arc(32, 32, 28, 0, 2 * Math.PI);
  g.fill();
  g.fillStyle = `#${color.toString(16).padStart(6, '0')}`;
  g.font = 'bold 36px system-ui, sans-serif';
  g.textAlign = 'center';
  g.textBaseline = 'middle';
  g.fillText(text, 32, 34);
  const sprite = new THREE.Sprite(
    new THREE.SpriteMaterial({ map: new THREE.CanvasTexture(canvas), depthTest: false, transparent: true }),
  );
  sprite.scale.set(size, size, 1);
  sprite.renderOrder = 4;
  return sprite;
}

/** One cut's disc, outline, normal stick and number, as a group. */
function disc({ point, normal, radius }, number, selected, numbered) {
  const color = selected ? SELECTED : COLOR;
  const r = DISC_SCALE * radius;
  const group = new THREE.Group();
  const face = new THREE.Mesh(
    new THREE.CircleGeometry(r, 48),
    new THREE.MeshBasicMaterial({
      color,
      transparent: true,
      opacity: selected ? 0.55 : 0.38,
      side: THREE.DoubleSide,
      depthWrite: false,
    }),
  );
  face.renderOrder = 3;
  const rim = new THREE.LineLoop(
    new THREE.BufferGeometry().setFromPoints(
      Array.from({ length: 48 }, (_, i) => {
        const a = (2 * Math.PI * i) / 48;
        return new THREE.Vector3(r * Math.cos(a), r * Math.sin(a), 0);
      }),
    ),
    new THREE.LineBasicMaterial({ color, depthTest: false, transparent: true, opacity: 0.9 }),
  );
  rim.renderOrder = 3;
  const stick = new THREE.Line(
    new THREE.BufferGeometry().setFromPoints([new THREE.Vector3(0, 0, 0), new THREE.Vector3(0, 0, 0.8 * r)]),
    new THREE.LineBasicMaterial({ color, depthTest: false }),
  );
  stick.renderOrder = 3;
  group.add(face, rim, stick);
  if (numbered) {
    const tag = label(String(number), radius, color);
    tag.position.set(r * 1.15, 0, 0);
    group.add(tag);
  }
  group.position.set(...point);
  group.quaternion.setFromUnitVectors(new THREE.Vector3(0, 0, 1), new THREE.Vector3(...normal).normalize());
  return group;
}

export class CutDiscs {
  /** @param {import('./viewer.js').Viewer} viewer */
  constructor(viewer) {
    this.viewer = viewer;
    this.group = null;
  }

  /**
   * Draws `cuts` ({point, normal, radius}; numbered from 1) with cut
   * `selected` (an index, or -1) highlighted; `made` (a flag a cut) leaves
   * the made cuts' numbers out; an empty list or hidden removes them.
   */
  show(cuts, selected = -1, visible = true, made = []) {
    this.clear();
    if (!visible || !cuts.length) return;
    this.group = new THREE.Group();
    cuts.forEach((c, i) => this.group.add(disc(c, i + 1, i === selected, !made[i] || i === selected)));
    this.viewer.addOverlay(this.group);
  }

  clear() {
    this.group = disposeOverlay(this.viewer, this.group);
  }
}
