// The side panel: the analysis of the loaded surface as text, the openings
// list (hover highlights a loop in the view; a radio button picks the inlet;
// after meshing, each opening shows the name of its cap) and the quality
// histogram.
import { drawHistogram } from './histogram.js';

const $ = (id) => document.getElementById(id);

const count = (n) => Number(n).toLocaleString('en-US');
const length = (x) => Number(x).toPrecision(4).replace(/\.?0+$/, '');
const point = (p) => `(${p.map(length).join(', ')})`;

/**
 * Fills the panel with `analysis` (the API's analysis object).
 * @param {(loop: number[] | null) => void} onHoverOpening
 */
export function showAnalysis(name, analysis, onHoverOpening) {
  const a = analysis;
  $('summary').hidden = false;
  $('file-name').textContent = name;
  $('stat-format').textContent = a.format === 'ascii' ? 'ASCII STL' : 'binary STL';
  $('stat-input-triangles').textContent = count(a.input_triangles);
  $('stat-vertices').textContent = count(a.vertices);
  $('stat-triangles').textContent = count(a.triangles);
  const bb = a.bounding_box;
  $('stat-bbox').textContent = `${point(bb.min)} – ${point(bb.max)}, diagonal ${length(bb.diagonal)}`;
  $('stat-components').textContent = String(a.components);
  $('stat-closed').textContent = a.closed ? 'yes' : 'no';
  $('stat-genus').textContent = a.genus === null ? 'undefined (non-manifold)' : String(a.genus);
  $('stat-nonmanifold').textContent = count(a.nonmanifold_edges);
  $('stat-openings').textContent = String(a.openings.length);

  const list = $('openings');
  list.replaceChildren();
  a.openings.forEach((o, i) => {
    const li = document.createElement('li');
    li.setAttribute('data-testid', 'opening-item');
    li.tabIndex = 0;
    // The inlet choice (the mesh option `inlet`, 1-based); the largest first.
    const choice = document.createElement('label');
    choice.className = 'inlet-choice';
    choice.title = 'Cap this opening as the inlet';
    const radio = document.createElement('input');
    radio.type = 'radio';
    radio.name = 'inlet';
    radio.value = String(i + 1);
    radio.checked = i === 0;
    radio.setAttribute('data-testid', 'inlet-choice');
    choice.append(radio, ' inlet');
    const text = document.createElement('span');
    text.textContent = `perimeter ${length(o.perimeter)}, radius ${length(o.radius)}, at ${point(o.centroid)}`;
    const cap = document.createElement('span');
    cap.className = 'cap-name';
    cap.setAttribute('data-testid', 'opening-cap');
    li.append(choice, ' ', text, ' ', cap);
    li.title = `Opening ${i + 1}: ${o.vertices.length} rim vertices`;
    const on = () => {
      li.classList.add('active');
      onHoverOpening(o.vertices);
    };
    const off = () => {
      li.classList.remove('active');
      onHoverOpening(null);
    };
    li.addEventListener('mouseenter', on);
    li.addEventListener('focus', on);
    li.addEventListener('mouseleave', off);
    li.addEventListener('blur', off);
    list.append(li);
  });

  $('quality-min').textContent = a.quality.min.toFixed(4);
  $('quality-mean').textContent = a.quality.mean.toFixed(4);
  drawHistogram($('histogram'), a.quality.histogram);

  const warnings = $('warnings');
  warnings.replaceChildren(
    ...a.warnings.map((w) => {
      const li = document.createElement('li');
      li.textContent = w;
      return li;
    }),
  );
  $('largest-only').checked = false;
}

/** The chosen inlet (1-based into analysis.openings), or undefined. */
export function chosenInlet() {
  const radio = $('openings').querySelector('input[name=inlet]:checked');
  return radio ? Number(radio.value) : undefined;
}

/**
 * Names each opening after the cap of the mesh that covers it (the nearest
 * cap centroid): data-cap and a label "→ inlet". No caps: names cleared.
 * @param {{name: string, centroid: number[]}[]} caps report.output.caps
 */
export function showCaps(openings, caps = []) {
  const items = $('openings').querySelectorAll('[data-testid=opening-item]');
  items.forEach((li, i) => {
    const c = openings[i].centroid;
    let best = null;
    let bestD = Infinity;
    for (const cap of caps) {
      const d = Math.hypot(...cap.centroid.map((x, k) => x - c[k]));
      if (d < bestD) [best, bestD] = [cap, d];
    }
    const name = best ? best.name : '';
    li.dataset.cap = name;
    li.querySelector('.cap-name').textContent = name ? `→ ${name}` : '';
  });
}

export function hideAnalysis() {
  $('summary').hidden = true;
}
