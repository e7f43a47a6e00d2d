// The surfaces as the file has them (the report's output.volume.surfaces:
// after boundary recovery, which may add points on the wall): a row a
// group with its triangles' gamma_k, the layers' ring at each opening (flat
// by construction) apart from the cap's disc.

/** Fills `table` (a thead and a tbody) with `surfaces` ({name, quality,
 * ring_quality?}); hidden when there are none. */
export function showSurfaceQuality(table, surfaces = []) {
  const fixed = (x) => x.toFixed(3);
  const rows = surfaces.map((s) => {
    const tr = document.createElement('tr');
    tr.dataset.group = s.name;
    const cells = [
      ['name', s.name],
      ['triangles', s.quality.count.toLocaleString('en')],
      ['min', s.quality.count ? fixed(s.quality.min) : '–'],
      ['mean', s.quality.count ? fixed(s.quality.mean) : '–'],
      ['ring-min', s.ring_quality ? `${fixed(s.ring_quality.min)} (${s.ring_quality.count.toLocaleString('en')})` : '–'],
    ];
    for (const [stat, text] of cells) {
      const td = document.createElement('td');
      td.dataset.stat = stat;
      td.textContent = text;
      tr.append(td);
    }
    return tr;
  });
  table.querySelector('tbody').replaceChildren(...rows);
  table.hidden = rows.length === 0;
}
