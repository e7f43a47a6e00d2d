// A capped SimVascular-like surface for the Node and Playwright tests.

/**
 * An ASCII VTK XML PolyData of a closed tube of radius 1 and length 4 with
 * flat ends, as SimVascular writes capped models: the wall labelled
 * ModelFaceID 1, the ends 2 and 3; n segments around, m along (the wall's
 * quads are split by the reader). Returns the file's text.
 */
export function cappedTubeVtp(n = 24, m = 8) {
  const points = [];
  for (let j = 0; j <= m; j++) {
    for (let i = 0; i < n; i++) {
      const a = (2 * Math.PI * i) / n;
      points.push(Math.cos(a), Math.sin(a), (4 * j) / m);
    }
  }
  const bottom = points.length / 3;
  points.push(0, 0, 0, 0, 0, 4);
  const polys = [];
  const labels = [];
  for (let j = 0; j < m; j++) {
    for (let i = 0; i < n; i++) {
      const a = j * n + i;
      const b = j * n + ((i + 1) % n);
      polys.push([a, b, b + n, a + n]);
      labels.push(1);
    }
  }
  for (let i = 0; i < n; i++) {
    polys.push([(i + 1) % n, i, bottom]);
    labels.push(2);
    polys.push([m * n + i, m * n + ((i + 1) % n), bottom + 1]);
    labels.push(3);
  }
  const offsets = [];
  let end = 0;
  for (const p of polys) offsets.push((end += p.length));
  return `<?xml version="1.0"?>
<VTKFile type="PolyData" version="1.0" byte_order="LittleEndian" header_type="UInt64">
  <PolyData>
    <Piece NumberOfPoints="${points.length / 3}" NumberOfPolys="${polys.length}">
      <CellData>
        <DataArray type="Int32" Name="ModelFaceID" format="ascii">${labels.join(' ')}</DataArray>
      </CellData>
      <Points>
        <DataArray type="Float64" NumberOfComponents="3" format="ascii">${points.join(' ')}</DataArray>
      </Points>
      <Polys>
        <DataArray type="Int64" Name="connectivity" format="ascii">${polys.flat().join(' ')}</DataArray>
        <DataArray type="Int64" Name="offsets" format="ascii">${offsets.join(' ')}</DataArray>
      </Polys>
    </Piece>
  </PolyData>
</VTKFile>
`;
}
