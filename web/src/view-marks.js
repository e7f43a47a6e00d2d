// Labels and marks drawn over the 3D view at model points, following the
// camera each frame: the openings' labels (their number in their colour;
// a click selects the opening's row, hovering highlights it), the places
// the preparation repaired (lettered marks: a re-surfaced crossing, a
// trimmed end) and the places a message names (a self-crossing, a failed
// patch: numbered red marks, buttons that zoom the view there). Opening
// labels hidden behind the surface shrink to dots, so the ones in sight
// read first. Labels that would cover one another are moved down, so
// every opening keeps a readable label, those in sight placed first.
const GAP_PX = 2;

function element(tag, className, testId) {
  const node = document.createElement(tag);
  node.className = className;
  node.setAttribute('data-testid', testId);
  return node;
}

/** '#rrggbb' of an RGB triple (0..1). */
export const cssColor = (rgb) =>
  `#${rgb.map((v) => Math.round(Math.min(1, Math.max(0, v)) * 255).toString(16).padStart(2, '0')).join('')}`;

/** Black or white, whichever reads better on the colour rgb (0..1). */
export function inkOn(rgb) {
  const lin = rgb.map((c) => (c <= 0.04045 ? c / 12.92 : ((c + 0.055) / 1.055) ** 2.4));
  const y = 0.2126 * lin[0] + 0.7152 * lin[1] + 0.0722 * lin[2];
  return (y + 0.05) / 0.05 > 1.05 / (y + 0.05) ? '#000000' : '#ffffff';
}

export class ViewMarks {
  /**
   * @param {import('./viewer.js').Viewer} viewer
   * @param {HTMLElement} container the view (positioned), the marks' parent
   */
  constructor(viewer, container) {
    this.viewer = viewer;
    this.layer = element('div', 'view-marks', 'view-marks');
    container.append(this.layer);
    this.openings = []; // {node, point}
    this.repairs = []; // {node, point}
    this.places = []; // {node, point}
    this.visible = { openings: true, repairs: true, places: true };
    viewer.onRender(() => this.update());
  }

  /**
   * The openings' labels: one per item {k, name, point, color (RGB 0..1)},
   * `onSelect(k)` on a click, `onHover(k | null)` as the pointer enters and
   * leaves. Hidden from assistive technology: the openings list says the
   * same, in the same numbers.
   */
  setOpenings(items, { onSelect = () => {}, onHover = () => {} } = {}) {
    for (const { node } of this.openings) node.remove();
    this.openings = items.map(({ k, name, point, color }) => {
      const node = element('span', 'opening-label', 'opening-label');
      node.textContent = String(k);
      node.title = `Opening ${k}: ${name}`;
      node.dataset.k = String(k);
      node.dataset.name = name;
      node.setAttribute('aria-hidden', 'true');
      node.style.background = cssColor(color);
      node.style.color = inkOn(color);
      node.addEventListener('click', () => onSelect(k));
      node.addEventListener('pointerenter', () => onHover(k));
      node.addEventListener('pointerleave', () => onHover(null));
      this.layer.append(node);
      return { node, point };
    });
    this.update();
  }

  /**
   * The places a message names: numbered buttons {point, radius, what}
   * that zoom the view there (`onZoom(i)` after), marked as warnings or
   * (tone 'info') as facts; none with [].
   */
  setPlaces(items, { onZoom = () => {}, tone = 'warn' } = {}) {
    for (const { node } of this.places) node.remove();
    this.places = items.map(({ point, radius = 0, what }, i) => {
      const node = element('button', `place-mark ${tone}`, 'place-mark');
      node.type = 'button';
      node.textContent = String(i + 1);
      const label = `Place ${i + 1}: ${what}. Zoom the view there`;
      node.setAttribute('aria-label', label);
      node.title = label;
      node.addEventListener('click', () => {
        this.viewer.focusOn(point, radius);
        onZoom(i);
      });
      this.layer.append(node);
      return { node, point };
    });
    this.update();
  }

  /**
   * The places the preparation repaired: lettered buttons {id, point,
   * radius, what} that zoom the view there; `onHover(id | null)` as the
   * pointer enters and leaves.
   */
  setRepairs(items, { onHover = () => {} } = {}) {
    for (const { node } of this.repairs) node.remove();
    this.repairs = items.map(({ id, point, radius = 0, what }) => {
      const node = element('button', 'repair-mark', 'repair-mark');
      node.type = 'button';
      node.textContent = id;
      node.dataset.id = id;
      const label = `Repair ${id}: ${what}. Zoom the view there`;
      node.setAttribute('aria-label', label);
      node.title = label;
      node.addEventListener('click', () => this.viewer.focusOn(point, radius));
      node.addEventListener('pointerenter', () => onHover(id));
      node.addEventListener('pointerleave', () => onHover(null));
      this.layer.append(node);
      return { node, point };
    });
    this.update();
  }

  /** Marks repair `id`'s mark as the one pointed at in the list (null: none). */
  activeRepair(id) {
    for (const { node } of this.repairs) node.classList.toggle('active', node.dataset.id === id);
  }

  /** Marks opening k's label as the one pointed at in the list (null: none). */
  activeOpening(k) {
    for (const { node } of this.openings) node.classList.toggle('active', node.dataset.k === String(k));
  }

  /** Shows or hides a kind of marks ('openings', 'repairs' or 'places'). */
  show(kind, on) {
    this.visible[kind] = on;
    this.update();
  }

  /** Puts every mark at its point's place in the view (hidden when behind
   * the camera or out of the view; opening labels behind the surface as
   * dots); labels that would overlap move down, those in sight placed
   * first. Sizes are read first, positions written after (one
   * layout a frame). */
  update() {
    const at = (m, on) => (on && this.viewer.sphere ? this.viewer.viewPoint(m.point) : null);
    // Places and repairs lie on or just inside the wall: always in full.
    const marks = [
      ...this.places.map((m) => ({ ...m, at: at(m, this.visible.places), behind: false })),
      ...this.repairs.map((m) => ({ ...m, at: at(m, this.visible.repairs), behind: false })),
      ...this.openings.map((m) => {
        const where = at(m, this.visible.openings);
        return { ...m, at: where, behind: Boolean(where) && this.viewer.hiddenBehind(m.point) };
      }),
    ];
    // The class first: a dot's size differs from a label's.
    for (const { node, behind } of marks) node.classList.toggle('behind', behind);
    const sizes = marks.map(({ node, at }) => (at ? [node.offsetWidth || 20, node.offsetHeight || 20] : null));
    const order = marks.map((_, i) => i).sort((i, j) => marks[i].behind - marks[j].behind);
    const placed = [];
    const moves = [];
    for (const i of order) {
      if (!marks[i].at) continue;
      const [w, h] = sizes[i];
      let [x, y] = [marks[i].at[0] - w / 2, marks[i].at[1] - h / 2];
      for (let tries = 0; tries < 6; tries++) {
        const hit = placed.find(
          (b) => x < b.x + b.w + GAP_PX && b.x < x + w + GAP_PX && y < b.y + b.h + GAP_PX && b.y < y + h + GAP_PX,
        );
        if (!hit) break;
        y = hit.y + hit.h + GAP_PX;
      }
      placed.push({ x, y, w, h });
      moves[i] = `translate(${Math.round(x)}px, ${Math.round(y)}px)`;
    }
    marks.forEach(({ node }, i) => {
      node.hidden = !moves[i];
      if (moves[i]) node.style.transform = moves[i];
    });
  }
}
