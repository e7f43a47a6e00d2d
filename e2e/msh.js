// A check of an exported Gmsh MSH 4.1 ASCII file, for the specs that take
// a model from load to export: the sections are there and consistent (every
// element's nodes exist, every element's entity belongs to a physical
// group), the tetrahedra are positively oriented (none inverted, none
// flat), and the physical groups are named.

/** The physical names, counts and problems of an MSH 4.1 text: {version,
 * groups: [{dim, tag, name}], nodes, elements: {type: count}, problems: []}. */
export function readMsh(text) {
  const lines = text.split('\n').map((l) => l.trim());
  const problems = [];
  const at = (name) => lines.indexOf(name);
  const version = lines[at('$MeshFormat') + 1]?.split(' ')[0];
  if (version !== '4.1') problems.push(`MSH version ${version}, not 4.1`);

  const groups = [];
  let i = at('$PhysicalNames');
  if (i < 0) problems.push('no $PhysicalNames');
  else {
    const n = Number(lines[i + 1]);
    for (let k = 0; k < n; k++) {
      const m = /^(\d+) (\d+) "(.*)"$/.exec(lines[i + 2 + k]);
      groups.push({ dim: Number(m[1]), tag: Number(m[2]), name: m[3] });
    }
  }

  // Entities: which physical tags each (dim, tag) entity has.
  const physical = new Map();
  i = at('$Entities');
  if (i < 0) problems.push('no $Entities');
  else {
    const counts = lines[i + 1].split(' ').map(Number);
    let row = i + 2;
    counts.forEach((count, dim) => {
      for (let k = 0; k < count; k++, row++) {
        const f = lines[row].split(' ').map(Number);
        const skip = dim === 0 ? 4 : 7; // tag, x y z (points) or the box
        physical.set(`${dim}:${f[0]}`, f.slice(skip + 1, skip + 1 + f[skip]));
      }
    });
  }

  const xyz = new Map();
  i = at('$Nodes') + 1;
  const blocks = Number(lines[i++].split(' ')[0]);
  for (let b = 0; b < blocks; b++) {
    const n = Number(lines[i++].split(' ')[3]);
    const tags = lines.slice(i, i + n).map(Number);
    i += n;
    tags.forEach((tag, k) => xyz.set(tag, lines[i + k].split(' ').map(Number)));
    i += n;
  }

  const elements = {};
  let inverted = 0;
  i = at('$Elements') + 1;
  const eblocks = Number(lines[i++].split(' ')[0]);
  for (let b = 0; b < eblocks; b++) {
    const [dim, entity, type, n] = lines[i++].split(' ').map(Number);
    if (!physical.get(`${dim}:${entity}`)?.length) problems.push(`entity ${dim}:${entity} has no physical group`);
    elements[type] = (elements[type] ?? 0) + n;
    for (const line of lines.slice(i, i + n)) {
      const nodes = line.split(' ').slice(1).map(Number);
      const points = nodes.map((t) => xyz.get(t));
      if (points.some((p) => !p)) {
        problems.push(`element ${line.split(' ')[0]} names a missing node`);
        continue;
      }
      if (type === 4) {
        const [a, c, d, e] = points;
        const u = c.map((x, k) => x - a[k]);
        const v = d.map((x, k) => x - a[k]);
        const w = e.map((x, k) => x - a[k]);
        const det = u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0]);
        if (!(det > 0)) inverted++;
      }
    }
    i += n;
  }
  if (inverted) problems.push(`${inverted} tetrahedra inverted or flat`);
  if (at('$EndElements') < 0) problems.push('no $EndElements');
  return { version, groups, nodes: xyz.size, elements, problems };
}
