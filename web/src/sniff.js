// What a file that is not a surface seems to be, by its first bytes (magic
// numbers), so the page can say so before the core is asked: an image, a
// PDF, an archive, a DICOM slice. Surfaces (STL, VTP, VTK, OBJ, PLY, any of
// them gzipped) and anything unknown pass: the core decides.

export const SUPPORTED = 'STL, VTP, VTK, OBJ or PLY surface files (any of them gzipped)';

const ascii = (bytes, at, text) => [...text].every((c, i) => bytes[at + i] === c.charCodeAt(0));
const starts = (bytes, magic) => magic.every((b, i) => bytes[i] === b);

// [what it seems to be, test on the first bytes]
const KINDS = [
  ['a PNG image', (b) => starts(b, [0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a])],
  ['a JPEG image', (b) => starts(b, [0xff, 0xd8, 0xff])],
  ['a GIF image', (b) => ascii(b, 0, 'GIF8')],
  ['a TIFF image', (b) => starts(b, [0x49, 0x49, 0x2a, 0x00]) || starts(b, [0x4d, 0x4d, 0x00, 0x2a])],
  ['a PDF document', (b) => ascii(b, 0, '%PDF-')],
  ['a ZIP archive', (b) => starts(b, [0x50, 0x4b, 0x03, 0x04]) || starts(b, [0x50, 0x4b, 0x05, 0x06])],
  ['a DICOM image (a scan slice, not a surface)', (b) => b.length >= 132 && ascii(b, 128, 'DICM')],
  ['a NIfTI volume image (a scan, not a surface)', (b) => b.length >= 348 && (ascii(b, 344, 'n+1\0') || ascii(b, 344, 'ni1\0'))],
];

/** What the file seems to be ('a PNG image'), or null when it may be a
 * surface. @param {Uint8Array} head the file's first bytes (512 suffice) */
export function sniffKind(head) {
  for (const [kind, test] of KINDS) if (test(head)) return kind;
  return null;
}

/**
 * The message for a file that is not a surface: what it seems to be and the
 * formats read; null when it may be one (the core reads it).
 * @param {Uint8Array} head the file's first bytes
 */
export function describeNonSurface(head) {
  const kind = sniffKind(head);
  return kind ? `this seems to be ${kind}, not a surface. vesselmesh reads ${SUPPORTED}.` : null;
}
