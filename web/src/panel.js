// The side panel: the analysis of the loaded surface as text, the openings
// list (hover highlights a loop in the view) and the quality histogram.
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
    li.dataset.testid = 'opening-item';
    li.setAttribute('data-testid', 'opening-item');
    li.tabIndex = 0;
    li.textContent = `perimeter ${length(o.perimeter)}, radius ${length(o.radius)}, at ${point(o.centroid)}`;
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

export function hideAnalysis() {
  $('summary').hidden = true;
}
