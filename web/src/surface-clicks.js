// Clicks on the 3D view, for the tools that pick a point of the surface
// (cuts, refinement spheres, measurements): a press and release within a few
// pixels is a click, a longer move an orbit (the camera's, not a pick).

/** How far (px) the pointer may move between press and release of a click. */
export const CLICK_SLOP_PX = 5;

/**
 * Listens on `view` (the element holding the viewer's canvas):
 * onClick(clientX, clientY) for each click on the canvas while active();
 * onHover(clientX, clientY), at most once an animation frame, while the
 * pointer moves and active(); onEscape() when Escape is pressed anywhere
 * while active().
 * @param {HTMLElement} view
 * @param {{active: () => boolean, onClick: (x: number, y: number) => void,
 *   onHover?: (x: number, y: number) => void, onEscape?: () => void}} hooks
 */
export function listenSurfaceClicks(view, { active, onClick, onHover, onEscape }) {
  let down = null;
  view.addEventListener('pointerdown', (e) => {
    down = { x: e.clientX, y: e.clientY };
  });
  let frame = 0;
  if (onHover) {
    view.addEventListener('pointermove', (e) => {
      if (!active() || frame) return;
      const { clientX: x, clientY: y } = e;
      frame = requestAnimationFrame(() => {
        frame = 0;
        if (active()) onHover(x, y);
      });
    });
  }
  view.addEventListener('pointerup', (e) => {
    if (!active() || !down || e.target.tagName !== 'CANVAS') return;
    if (Math.hypot(e.clientX - down.x, e.clientY - down.y) > CLICK_SLOP_PX) return;
    onClick(e.clientX, e.clientY);
  });
  if (onEscape) {
    document.addEventListener('keydown', (e) => {
      if (e.key === 'Escape' && active()) onEscape();
    });
  }
}

/**
 * Shows a click mode on or off: its toggle button pressed and labelled, its
 * "at the view's centre" button shown, the picking cursor on the view and,
 * when on, the hint in #pick-info (hidden when off).
 * @param {boolean} on
 * @param {{button: string, centre: string, onLabel: string, offLabel: string,
 *   hint: string}} mode the ids of the two buttons, the toggle's labels
 */
export function showClickMode(on, { button, centre, onLabel, offLabel, hint }) {
  const $ = (id) => document.getElementById(id);
  $(button).setAttribute('aria-pressed', String(on));
  $(button).textContent = on ? onLabel : offLabel;
  $(centre).hidden = !on;
  $('viewer').classList.toggle('picking', on);
  $('pick-info').hidden = !on;
  if (on) $('pick-info').textContent = hint;
}

/** The page coordinates of the centre of the viewer's canvas: where a
 * keyboard user aims by orbiting the view (arrow keys). */
export function viewCentre(viewer) {
  const rect = viewer.renderer.domElement.getBoundingClientRect();
  return [rect.left + rect.width / 2, rect.top + rect.height / 2];
}
