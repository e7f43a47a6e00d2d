// The Transferable list of an API result: the buffers of its typed arrays,
// each once (a repeated buffer makes postMessage throw), so a result crosses
// from the worker to the page moved, not copied (a volume of 1M tetrahedra
// is ~60 MB). The sender's arrays are detached afterwards.

/** @returns {ArrayBuffer[]} the buffers of file, msh, stl, vtp, surface.*, volume.*
 * and sizeField()'s positions, triangles, radius and size */
export function transferables(result) {
  const buffers = new Set();
  const add = (a) => ArrayBuffer.isView(a) && buffers.add(a.buffer);
  if (result && result.ok) {
    add(result.file);
    add(result.msh);
    add(result.stl);
    add(result.vtp);
    for (const key of ['positions', 'triangles', 'radius', 'size']) add(result[key]);
    for (const part of [result.surface, result.volume]) {
      if (part) Object.values(part).forEach(add);
    }
  }
  return [...buffers];
}
