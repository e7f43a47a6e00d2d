// Kept boundary-layer prisms, shown in the clipped view as the tetrahedra
// they split into and their quads at the openings as two triangles each:
// the view then works on tetrahedra only. The split and the tetrahedra's
// gamma_t come from the core (volume.prismTets, prismTetQuality,
// quadTriangles: the smallest-index diagonal rule, so neighbours agree);
// here they are only appended. The exported files keep the prisms.

/**
 * A volume with kept prisms (volume.prisms) as one of tetrahedra only: the
 * prisms' tetrahedra (their part: 2 in the vessel wall's region, else 1)
 * and the quads' triangles appended; the other fields kept. Volumes
 * without prisms are returned as they are.
 */
export function withPrismsSplit(volume) {
  if (!volume?.prisms?.length) return volume;
  const { tets, tetQuality, tetRegion, prismRegion, prismTets, prismTetQuality, quadTriangles, quadTag } = volume;
  const nt = tets.length / 4;
  const n = nt + prismTets.length / 4;
  const append = (Type, a, b) => {
    const out = new Type(a.length + b.length);
    out.set(a);
    out.set(b, a.length);
    return out;
  };
  const region = new Int32Array(n);
  region.set(tetRegion);
  const part = new Uint8Array(n);
  part.set(volume.tetPart ?? new Uint8Array(nt));
  const wall = volume.regionNames.indexOf('vessel_wall');
  for (let t = nt; t < n; t++) {
    region[t] = prismRegion[Math.floor((t - nt) / 3)];
    part[t] = region[t] === wall ? 2 : 1;
  }
  const quadTags = new Int32Array(quadTriangles.length / 3);
  quadTags.forEach((_, i) => (quadTags[i] = quadTag[i >> 1]));
  return {
    ...volume,
    tets: append(Uint32Array, tets, prismTets),
    tetQuality: append(Float32Array, tetQuality, prismTetQuality),
    tetRegion: region,
    tetPart: part,
    triangles: append(Uint32Array, volume.triangles, quadTriangles),
    triangleTag: append(Int32Array, volume.triangleTag, quadTags),
  };
}
