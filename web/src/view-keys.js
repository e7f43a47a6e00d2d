// The 3D view by keyboard: the canvas is focusable (tab to it) and, while it
// has focus, the arrow keys orbit the camera around the model, + and -
// zoom, 0 fits the view.
const STEP = Math.PI / 24; // 7.5° a press

const KEYS = {
  ArrowLeft: (v) => v.orbit(-STEP, 0),
  ArrowRight: (v) => v.orbit(STEP, 0),
  ArrowUp: (v) => v.orbit(0, -STEP),
  ArrowDown: (v) => v.orbit(0, STEP),
  '+': (v) => v.zoom(1 / 1.2),
  '=': (v) => v.zoom(1 / 1.2),
  '-': (v) => v.zoom(1.2),
  _: (v) => v.zoom(1.2),
  0: (v) => v.fitView(),
};

/** Makes the viewer's canvas focusable, named, and driven by the keys. */
export function listenViewKeys(viewer) {
  const canvas = viewer.renderer.domElement;
  canvas.tabIndex = 0;
  canvas.setAttribute('role', 'application');
  canvas.setAttribute('aria-roledescription', '3D view');
  canvas.setAttribute('aria-label', '3D view of the model: arrow keys rotate, + and - zoom, 0 fits the view');
  canvas.dataset.testid = 'view-canvas';
  canvas.addEventListener('keydown', (e) => {
    if (e.ctrlKey || e.metaKey || e.altKey) return;
    const act = KEYS[e.key];
    if (!act) return;
    e.preventDefault();
    act(viewer);
  });
}
