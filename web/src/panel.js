// The side panel's summary of the loaded surface: the file's format, its
// length unit (and the question to confirm it when it was guessed without
// certainty), counts, bounding box, caps, the quality histogram and the
// analysis' warnings (but those the repairs list: repair-places.js). The
// openings table is openings.js.
import { drawHistogram } from './histogram.js';
import { saidAsRepair } from './repair-places.js';
import { point, unitsQuestion, unitsText, withUnit } from './units.js';
import { inputQualityNote } from './verdict.js';
import { inPageWords } from './words.js';

const $ = (id) => document.getElementById(id);

const count = (n) => Number(n).toLocaleString('en-US');

/** The caps row: how many planar caps were removed, and by which face labels. */
function capsText(a, keepCaps) {
  if (keepCaps) return 'kept as wall';
  if (!a.caps_removed) return 'none found';
  return `${count(a.caps_removed)} removed${a.label_array ? ` (faces labelled by ${a.label_array})` : ''}`;
}

/** The unit row and, when the guess is not certain, the question. */
function showUnits(units) {
  $('stat-units').textContent = unitsText(units);
  const question = unitsQuestion(units);
  $('units-prompt').hidden = !question;
  $('units-question').textContent = question ?? '';
}

/**
 * Fills the panel with `analysis` (the API's analysis object) of the file
 * `name`, read with `prep` (the analyze options: keepCaps...).
 */
export function showAnalysis(name, analysis, prep) {
  const a = analysis;
  const unit = a.units.unit;
  $('summary').hidden = false;
  $('intro').hidden = true;
  $('file-name').textContent = name;
  showUnits(a.units);
  $('stat-format').textContent = a.format;
  $('stat-input-triangles').textContent = count(a.input_triangles);
  $('stat-vertices').textContent = count(a.vertices);
  $('stat-triangles').textContent = count(a.triangles);
  const bb = a.bounding_box;
  const [lo, hi] = [point(bb.min, bb.diagonal), point(bb.max, bb.diagonal)];
  $('stat-bbox').textContent = `${lo} – ${hi} ${unit}, diagonal ${withUnit(bb.diagonal, unit)}`;
  $('stat-components').textContent = String(a.components);
  $('stat-closed').textContent = a.closed ? 'yes' : 'no';
  $('stat-genus').textContent = a.genus === null ? 'undefined (non-manifold)' : String(a.genus);
  $('stat-nonmanifold').textContent = count(a.nonmanifold_edges);
  $('stat-caps').textContent = capsText(a, prep.keepCaps);
  $('stat-openings').textContent = String(a.openings.length);

  $('quality-min').textContent = a.quality.min.toPrecision(2);
  $('quality-mean').textContent = a.quality.mean.toFixed(3);
  const note = inputQualityNote(a.quality);
  $('quality-note').textContent = note;
  $('quality-note').hidden = !note;
  drawHistogram($('histogram'), a.quality.histogram);

  // The repairs with a place are listed by the repairs (repair-places.js).
  $('warnings').replaceChildren(
    ...a.warnings.filter((w) => !saidAsRepair(w)).map((w) => {
      const li = document.createElement('li');
      li.textContent = inPageWords(w, { unit, scale: bb.diagonal });
      return li;
    }),
  );
}

export function hideAnalysis() {
  $('summary').hidden = true;
  $('intro').hidden = false;
}
