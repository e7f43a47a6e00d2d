// A surface that crosses itself, for the Node and Playwright tests.

/**
 * An ASCII STL of an open tube of radius 1 along z (0 to 8; 48 segments
 * around, 40 along) whose wall near (1, 0, 4) is pushed 2.6 towards -x,
 * through the opposite wall (x = -1): it crosses itself in one place, near
 * (-1, 0, 4). Returns the file's text.
 */
export function dentedTubeStl() {
  const n = 48;
  const m = 40;
  const p = [];
  for (let j = 0; j <= m; ++j) {
    for (let i = 0; i < n; ++i) {
      const a = (2 * Math.PI * i) / n;
      const z = (8 * j) / m;
      const d2 = 2 * (1 - Math.cos(a)) + (z - 4) ** 2;
      p.push([Math.cos(a) - 2.6 * Math.exp(-d2 / (2 * 0.35 ** 2)), Math.sin(a), z]);
    }
  }
  let stl = 'solid dent\n';
  for (let j = 0; j < m; ++j) {
    for (let i = 0; i < n; ++i) {
      const a = j * n + i;
      const b = j * n + ((i + 1) % n);
      for (const t of [
        [a, b, b + n],
        [a, b + n, a + n],
      ]) {
        stl += `facet normal 0 0 0\nouter loop\n${t.map((v) => `vertex ${p[v].join(' ')}\n`).join('')}endloop\nendfacet\n`;
      }
    }
  }
  return `${stl}endsolid dent\n`;
}
