// File names and formats of the page: the surface files it opens (the core
// recognises the format by content; the names only guide the picker and the
// exported file's name) and the files it exports.

/** The extensions of the surface files the core reads (any of them may be gzipped). */
export const SURFACE_EXTENSIONS = ['.stl', '.vtp', '.vtk', '.obj', '.ply'];

/** The file input's accept list. */
export const ACCEPT = [...SURFACE_EXTENSIONS, '.gz', 'model/stl', 'application/sla'].join(',');

const SURFACE_NAME = new RegExp(`(${SURFACE_EXTENSIONS.map((e) => `\\${e}`).join('|')})?(\\.gz)?$`, 'i');

/** The name of a surface file without its extensions: 'aorta.vtp.gz' -> 'aorta'. */
export function baseName(name) {
  const base = name.replace(SURFACE_NAME, '');
  return base === '' ? 'mesh' : base;
}

/**
 * The export formats offered: the select's value, its label, the API's
 * `format`, `mshVersion`, `mshBinary`, `vtkCompress` and `foamBinary`, the
 * file's suffix after the base name, its MIME type, and whether it needs
 * the volume (not a surface-only result).
 */
export const EXPORT_FORMATS = [
  { value: 'msh-4.1', label: 'MSH 4.1 (Gmsh)', format: 'msh', mshVersion: '4.1', suffix: '.msh', mime: 'text/plain' },
  { value: 'msh-2.2', label: 'MSH 2.2 (Gmsh)', format: 'msh', mshVersion: '2.2', suffix: '.msh', mime: 'text/plain' },
  {
    value: 'msh-4.1-binary',
    label: 'MSH 4.1 binary (Gmsh)',
    format: 'msh',
    mshVersion: '4.1',
    mshBinary: true,
    suffix: '.msh',
    mime: 'application/octet-stream',
  },
  { value: 'vtu', label: 'VTU volume', format: 'vtu', suffix: '.vtu', mime: 'application/xml', volume: true },
  {
    value: 'vtu-compressed',
    label: 'VTU volume, zlib-compressed',
    format: 'vtu',
    vtkCompress: true,
    suffix: '.vtu',
    mime: 'application/xml',
    volume: true,
  },
  { value: 'vtp', label: 'VTP boundary faces', format: 'vtp', suffix: '-boundary.vtp', mime: 'application/xml' },
  { value: 'stl', label: 'STL wall', format: 'stl', suffix: '-wall.stl', mime: 'model/stl' },
  {
    value: 'mesh-complete',
    label: 'SimVascular mesh-complete (.zip)',
    format: 'mesh-complete',
    suffix: '-mesh-complete.zip',
    mime: 'application/zip',
    volume: true,
  },
  {
    value: 'foam',
    label: 'OpenFOAM case, polyMesh (.zip)',
    format: 'foam',
    suffix: '-openfoam.zip',
    mime: 'application/zip',
    volume: true,
  },
  {
    value: 'foam-binary',
    label: 'OpenFOAM case, binary polyMesh (.zip)',
    format: 'foam',
    foamBinary: true,
    suffix: '-openfoam.zip',
    mime: 'application/zip',
    volume: true,
  },
];

/** The export format with this select value (the first, MSH 4.1, if unknown). */
export function exportFormat(value) {
  return EXPORT_FORMATS.find((f) => f.value === value) ?? EXPORT_FORMATS[0];
}

/** The exported file's name: the input's base name and the format's suffix. */
export function exportFileName(inputName, value) {
  return baseName(inputName) + exportFormat(value).suffix;
}
