// Opening a surface: the file picker (Open surface...), a file dropped on
// the view, the generated sample (Load sample). A file that is no surface
// at all (an image, a PDF, an archive, a DICOM slice), too large for a
// browser tab or unreadable is refused here, before the core is asked.
import { describeNonSurface } from './sniff.js';

const $ = (id) => document.getElementById(id);
// Above this the browser tab would run out of memory (the wasm heap is 4 GB).
const MAX_FILE_BYTES = 1.5 * 2 ** 30;

/** A file's bytes, or why it is refused: {bytes} or {error}. */
export async function readSurface(file) {
  const head = new Uint8Array(await file.slice(0, 512).arrayBuffer().catch(() => new ArrayBuffer(0)));
  const wrong = describeNonSurface(head, file.name);
  if (wrong) return { error: `${file.name}: ${wrong}` };
  if (file.size > MAX_FILE_BYTES) {
    return { error: `${file.name}: file too large (${(file.size / 2 ** 30).toFixed(1)} GB; the limit in a browser tab is 1.5 GB).` };
  }
  try {
    return { bytes: new Uint8Array(await file.arrayBuffer()) };
  } catch (e) {
    return { error: `${file.name}: cannot read the file (${e.message}).` };
  }
}

/**
 * Follows the ways to open a surface.
 * @param {object} hooks
 * @param {(file: File) => void} hooks.onFile a file picked or dropped
 * @param {() => void} hooks.onSample Load sample pressed
 */
export function listenOpen({ onFile, onSample }) {
  $('file-input').addEventListener('change', (e) => {
    const file = e.target.files[0];
    e.target.value = '';
    if (file) onFile(file);
  });
  $('load-sample').addEventListener('click', onSample);
  $('open-file').addEventListener('click', () => $('file-input').click());
  const view = $('viewer');
  view.addEventListener('dragover', (e) => {
    e.preventDefault();
    view.classList.add('dragging');
  });
  view.addEventListener('dragleave', () => view.classList.remove('dragging'));
  view.addEventListener('drop', (e) => {
    e.preventDefault();
    view.classList.remove('dragging');
    const file = e.dataTransfer.files[0];
    if (file) onFile(file);
  });
}
