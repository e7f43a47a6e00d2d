// Overlays drawn over the surface (cut discs, hole markers, refinement
// balls): removing one from the view and freeing its GPU resources.

/** Removes `group` (added with viewer.addOverlay) and disposes of its
 * geometries, materials and textures; returns null for the caller's field. */
export function disposeOverlay(viewer, group) {
  if (!group) return null;
  viewer.removeOverlay(group);
  group.traverse((obj) => {
    obj.geometry?.dispose();
    obj.material?.map?.dispose();
    obj.material?.dispose();
  });
  return null;
}
