// The export: the format select (the formats of files.js; those that need
// the volume off for a surface-only mesh), the Export button named after
// the chosen format, the options of the file to write (format, MSH
// version and binary, VTK compression, OpenFOAM binary, output units), and the press: the file written again from the
// worker's last mesh when that has the panel's options, else meshed
// first; then downloaded, named after the input.
import { EXPORT_FORMATS, exportFileName, exportFormat } from './files.js';

const $ = (id) => document.getElementById(id);

/** Downloads `bytes` (a Uint8Array, never decoded: binary MSH stays
 * bytes) as a file `name` of MIME type `type`. */
export function download(name, bytes, type) {
  const url = URL.createObjectURL(new Blob([bytes], { type }));
  const a = document.createElement('a');
  a.href = url;
  a.download = name;
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10_000);
}

/** Fills the format select with the export formats. */
export function fillExportFormats() {
  $('format').replaceChildren(...EXPORT_FORMATS.map(({ value, label }) => new Option(label, value)));
}

/** The chosen file format and units to write: export() and mesh() options. */
export function writeOptions() {
  const { format, mshVersion, mshBinary, vtkCompress, foamBinary } = exportFormat($('format').value);
  const outputUnits = $('output-units').value;
  return {
    format,
    ...(mshVersion && { mshVersion }),
    ...(mshBinary && { mshBinary }),
    ...(vtkCompress && { vtkCompress }),
    ...(foamBinary && { foamBinary }),
    ...(outputUnits && { outputUnits }),
  };
}

/** The export formats that apply: a surface-only mesh has no volume formats. */
export function syncExportFormats() {
  const surfaceOnly = $('surface-only').checked;
  for (const option of $('format').options) {
    option.disabled = surfaceOnly && exportFormat(option.value).volume === true;
  }
  if ($('format').selectedOptions[0]?.disabled) $('format').value = EXPORT_FORMATS[0].value;
  $('export-hint').hidden = !surfaceOnly;
  showExportLabel();
}

/** The Export button names the chosen format: 'Export MSH 4.1'. */
export function showExportLabel() {
  const { label } = exportFormat($('format').value);
  $('export').textContent = `Export ${label.replace(/ \(.*\)$/, '')}`;
}

/**
 * The Export press: downloads the mesh of `options` (the panel's mesh
 * options, checked) in the chosen format.
 * @param {object} options
 * @param {object} hooks
 * @param {() => string} hooks.inputName the loaded file's name
 * @param {(options: object) => boolean} hooks.held whether the worker's last
 *   mesh is the one of these options (then only written again)
 * @param {(format: string, write: object) => Promise<Uint8Array|null>} hooks.exportHeld
 *   writes the worker's last mesh (null on failure, said)
 * @param {(options: object, write: object) => Promise<object|null>} hooks.meshWith
 *   meshes with `options` and writes the file (the result, or null, said)
 * @param {(name: string) => void} hooks.onDone
 */
export async function exportFile(options, { inputName, held, exportHeld, meshWith, onDone }) {
  const { format, ...write } = writeOptions();
  const file = held(options) ? await exportHeld(format, write) : (await meshWith(options, { format, ...write }))?.file;
  const chosen = exportFormat($('format').value);
  if (file) {
    const name = exportFileName(inputName(), chosen.value);
    download(name, file, chosen.mime);
    onDone(name);
  }
}
