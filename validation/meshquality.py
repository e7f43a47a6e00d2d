"""Quality measures of the seed paper (section 3), computed from node
coordinates so that vesselmesh's and Gmsh's meshes are judged by the same
formula, plus a minimal reader of Gmsh MSH 4.1 / 2.2 ASCII files and SVG
histograms in the style of the seed's Fig. 6 (no plotting dependency).

  gamma_k = 4 sin a sin b sin c / (sin a + sin b + sin c) = 2 r_in / r_circ
          = 16 A^2 / ((l1 + l2 + l3) l1 l2 l3)
  gamma_t = 6 sqrt(6) V / (sum of the 4 face areas * longest edge)

Needs numpy.
"""
import math

import numpy as np

HIST_BINS = 100  # over [0, 1]; Fig. 6 panels are [0, 0.6] and [0.6, 1]


def gamma_k(xyz, tri):
    """xyz: (n, 3) float, tri: (m, 3) int (0-based) -> (m,) gamma_k."""
    tri = np.asarray(tri, dtype=np.int64)
    if len(tri) == 0:
        return np.zeros(0)
    p0, p1, p2 = xyz[tri[:, 0]], xyz[tri[:, 1]], xyz[tri[:, 2]]
    l0 = np.linalg.norm(p1 - p2, axis=1)
    l1 = np.linalg.norm(p2 - p0, axis=1)
    l2 = np.linalg.norm(p0 - p1, axis=1)
    area2 = np.linalg.norm(np.cross(p1 - p0, p2 - p0), axis=1)  # 2 A
    den = (l0 + l1 + l2) * l0 * l1 * l2
    with np.errstate(divide="ignore", invalid="ignore"):
        g = 4.0 * area2 * area2 / den  # 16 A^2 = 4 (2A)^2
    return np.clip(np.nan_to_num(g, nan=0.0), 0.0, 1.0)


def gamma_t(xyz, tet):
    """xyz: (n, 3), tet: (m, 4) int (0-based) -> (m,) gamma_t (unsigned volume)."""
    tet = np.asarray(tet, dtype=np.int64)
    if len(tet) == 0:
        return np.zeros(0)
    a, b, c, d = (xyz[tet[:, i]] for i in range(4))
    vol = np.abs(np.einsum("ij,ij->i", b - a, np.cross(c - a, d - a))) / 6.0

    def area(p, q, r):
        return 0.5 * np.linalg.norm(np.cross(q - p, r - p), axis=1)

    s = area(a, b, c) + area(a, b, d) + area(a, c, d) + area(b, c, d)
    edges = [b - a, c - a, d - a, c - b, d - b, d - c]
    lmax = np.max(np.stack([np.linalg.norm(e, axis=1) for e in edges]), axis=0)
    with np.errstate(divide="ignore", invalid="ignore"):
        g = 6.0 * math.sqrt(6.0) * vol / (s * lmax)
    return np.clip(np.nan_to_num(g, nan=0.0), 0.0, 1.0)


def signed_tet_volumes(xyz, tet):
    tet = np.asarray(tet, dtype=np.int64)
    a, b, c, d = (xyz[tet[:, i]] for i in range(4))
    return np.einsum("ij,ij->i", b - a, np.cross(c - a, d - a)) / 6.0


def median_edge(xyz, cells):
    """Median length of the distinct edges of triangles (m, 3) or tetrahedra
    (m, 4)."""
    cells = np.asarray(cells, dtype=np.int64)
    if len(cells) == 0:
        return float("nan")
    k = cells.shape[1]
    e = np.concatenate([cells[:, [i, j]] for i in range(k) for j in range(i + 1, k)])
    e.sort(axis=1)
    e = np.unique(e, axis=0)
    return float(np.median(np.linalg.norm(xyz[e[:, 0]] - xyz[e[:, 1]], axis=1)))


def summary(q, bins=HIST_BINS):
    """min / mean / count and a histogram of `bins` equal bins over [0, 1]."""
    q = np.asarray(q, dtype=float)
    if len(q) == 0:
        return dict(min=None, mean=None, count=0, bins=bins, histogram=[0] * bins)
    idx = np.clip((q * bins).astype(np.int64), 0, bins - 1)
    return dict(min=float(q.min()), mean=float(q.mean()), count=int(len(q)), bins=bins,
                histogram=np.bincount(idx, minlength=bins).tolist(),
                below={str(t): int((q < t).sum()) for t in (0.1, 0.2, 0.3, 0.5)})


# ---------------------------------------------------------------- MSH reader

def read_msh(path):
    """Reads an ASCII Gmsh MSH 4.1 or 2.2 file. Returns (xyz (n,3), elements)
    where elements maps Gmsh element type (2 triangle, 4 tet, 6 prism) to a
    0-based (m, k) int array. Node tags are remapped to rows of xyz."""
    with open(path, "r") as f:
        lines = f.read().split("\n")
    i = 0
    version = None
    tags, coords = [], []
    elems = {}
    nodes_per = {1: 2, 2: 3, 3: 4, 4: 4, 5: 8, 6: 6, 7: 5, 15: 1}
    while i < len(lines):
        s = lines[i].strip()
        if s == "$MeshFormat":
            version = lines[i + 1].split()[0]
            if lines[i + 1].split()[1] != "0":
                raise ValueError(f"{path}: binary MSH not supported")
            i += 2
        elif s == "$Nodes":
            i += 1
            if version.startswith("4"):
                nblocks = int(lines[i].split()[0])
                i += 1
                for _ in range(nblocks):
                    n = int(lines[i].split()[3])
                    i += 1
                    tags.append(np.array(lines[i:i + n], dtype=np.int64) if n else np.zeros(0, np.int64))
                    i += n
                    if n:
                        coords.append(np.loadtxt(lines[i:i + n], ndmin=2)[:, :3])
                    i += n
            else:
                n = int(lines[i])
                i += 1
                block = np.loadtxt(lines[i:i + n], ndmin=2)
                tags.append(block[:, 0].astype(np.int64))
                coords.append(block[:, 1:4])
                i += n
        elif s == "$Elements":
            i += 1
            if version.startswith("4"):
                nblocks = int(lines[i].split()[0])
                i += 1
                for _ in range(nblocks):
                    _, _, etype, n = (int(x) for x in lines[i].split())
                    i += 1
                    if n:
                        arr = np.loadtxt(lines[i:i + n], dtype=np.int64, ndmin=2)[:, 1:]
                        elems.setdefault(etype, []).append(arr)
                    i += n
            else:
                n = int(lines[i])
                i += 1
                for ln in lines[i:i + n]:
                    v = [int(x) for x in ln.split()]
                    etype, ntags = v[1], v[2]
                    elems.setdefault(etype, []).append(np.array([v[3 + ntags:3 + ntags + nodes_per[etype]]]))
                i += n
        else:
            i += 1
    tag = np.concatenate(tags) if tags else np.zeros(0, np.int64)
    xyz = np.concatenate(coords) if coords else np.zeros((0, 3))
    remap = np.full(int(tag.max()) + 1 if len(tag) else 1, -1, dtype=np.int64)
    remap[tag] = np.arange(len(tag))
    out = {t: remap[np.concatenate(v)] for t, v in elems.items()}
    return xyz, out


def msh_quality(path):
    """gamma_k of the triangles and gamma_t of the tets of an MSH file."""
    xyz, el = read_msh(path)
    tri = el.get(2, np.zeros((0, 3), np.int64))
    tet = el.get(4, np.zeros((0, 4), np.int64))
    r = dict(nodes=int(len(xyz)), triangles=int(len(tri)), tets=int(len(tet)),
             gamma_k=summary(gamma_k(xyz, tri)), median_edge=median_edge(xyz, tri))
    if len(tet):
        r["gamma_t"] = summary(gamma_t(xyz, tet))
        r["median_tet_edge"] = median_edge(xyz, tet)
    return r


# ---------------------------------------------------------------- distances

def read_stl_points(path):
    """The distinct corner points of a binary or ASCII STL file, (n, 3)."""
    with open(path, "rb") as f:
        data = f.read()
    n = int(np.frombuffer(data, np.uint32, 1, 80)[0]) if len(data) >= 84 else -1
    if n >= 0 and len(data) == 84 + 50 * n:
        rec = np.dtype([("normal", "<f4", 3), ("v", "<f4", (3, 3)), ("attr", "<u2")])
        pts = np.frombuffer(data, rec, n, 84)["v"].reshape(-1, 3).astype(np.float64)
    else:
        words = data.decode("ascii", "replace").split()
        idx = [i for i, w in enumerate(words) if w == "vertex"]
        pts = np.array([[float(words[i + 1]), float(words[i + 2]), float(words[i + 3])]
                        for i in idx]).reshape(-1, 3)
    return np.unique(pts, axis=0)


def _closest_on_triangles(p, a, b, c):
    """Closest points to p on triangles (a, b, c), all (m, 3) (Ericson,
    Real-Time Collision Detection, 5.1.5, region by region)."""
    ab, ac, ap = b - a, c - a, p - a
    d1, d2 = np.einsum("ij,ij->i", ab, ap), np.einsum("ij,ij->i", ac, ap)
    bp, cp = p - b, p - c
    d3, d4 = np.einsum("ij,ij->i", ab, bp), np.einsum("ij,ij->i", ac, bp)
    d5, d6 = np.einsum("ij,ij->i", ab, cp), np.einsum("ij,ij->i", ac, cp)
    va, vb, vc = d3 * d6 - d5 * d4, d5 * d2 - d1 * d6, d1 * d4 - d3 * d2
    with np.errstate(divide="ignore", invalid="ignore"):
        denom = va + vb + vc
        v, w = vb / denom, vc / denom
        out = a + ab * v[:, None] + ac * w[:, None]  # inside the face
        # Edges, then vertices (later assignments take precedence).
        t = d1 / (d1 - d3)
        m = (vc <= 0) & (d1 >= 0) & (d3 <= 0)
        out[m] = (a + ab * t[:, None])[m]
        t = d2 / (d2 - d6)
        m = (vb <= 0) & (d2 >= 0) & (d6 <= 0)
        out[m] = (a + ac * t[:, None])[m]
        t = (d4 - d3) / ((d4 - d3) + (d5 - d6))
        m = (va <= 0) & (d4 - d3 >= 0) & (d5 - d6 >= 0)
        out[m] = (b + (c - b) * t[:, None])[m]
    out[(d1 <= 0) & (d2 <= 0)] = a[(d1 <= 0) & (d2 <= 0)]
    out[(d3 >= 0) & (d4 <= d3)] = b[(d3 >= 0) & (d4 <= d3)]
    out[(d6 >= 0) & (d5 <= d6)] = c[(d6 >= 0) & (d5 <= d6)]
    return out


def distances_within(points, xyz, tri, radius):
    """Per point (n, 3), its distance to the nearest triangle (xyz (k, 3),
    tri (m, 3) 0-based) when that is at most `radius`, else inf. Triangles
    are binned in a grid of cells of at least `radius`; a point meets those
    whose box, grown by `radius`, covers its cell."""
    corners = xyz[tri]
    lo, hi = corners.min(axis=1) - radius, corners.max(axis=1) + radius
    cell = max(radius, float(np.median(hi - lo)))
    origin = lo.min(axis=0)
    clo = np.floor((lo - origin) / cell).astype(np.int64)
    chi = np.floor((hi - origin) / cell).astype(np.int64)
    dims = chi.max(axis=0) + 2
    span = chi - clo
    keys, owners = [], []
    for dx in range(int(span[:, 0].max()) + 1):
        for dy in range(int(span[:, 1].max()) + 1):
            for dz in range(int(span[:, 2].max()) + 1):
                m = (span[:, 0] >= dx) & (span[:, 1] >= dy) & (span[:, 2] >= dz)
                c = clo[m] + [dx, dy, dz]
                keys.append((c[:, 0] * dims[1] + c[:, 1]) * dims[2] + c[:, 2])
                owners.append(np.nonzero(m)[0])
    keys, owners = np.concatenate(keys), np.concatenate(owners)
    order = np.argsort(keys, kind="stable")
    keys, owners = keys[order], owners[order]
    dist = np.full(len(points), np.inf)
    pc = np.floor((points - origin) / cell).astype(np.int64)
    inside = np.all((pc >= 0) & (pc < dims), axis=1)
    idx = np.nonzero(inside)[0]
    pk = (pc[idx, 0] * dims[1] + pc[idx, 1]) * dims[2] + pc[idx, 2]
    first, last = np.searchsorted(keys, pk, "left"), np.searchsorted(keys, pk, "right")
    count = last - first
    pt = np.repeat(idx, count)
    starts = np.repeat(first - np.cumsum(count) + count, count) + np.arange(count.sum())
    tr = owners[starts]
    q = _closest_on_triangles(points[pt], corners[tr, 0], corners[tr, 1], corners[tr, 2])
    d = np.linalg.norm(points[pt] - q, axis=1)
    np.minimum.at(dist, pt, d)
    dist[dist > radius] = np.inf
    return dist


# ---------------------------------------------------------------- SVG plots

PALETTE = ["#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b",
           "#e377c2", "#7f7f7f", "#bcbd22", "#17becf", "#000000"]


def _esc(s):
    return str(s).replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def svg_histograms(series, title, path, panels=((0.0, 0.6), (0.6, 1.0)), xlabel="gamma_k", plot_bins=50):
    """Fig. 6-style plot: one line per series (percentage of elements per bin
    against bin center), one panel per range. series: list of (label,
    histogram counts over [0, 1] with len(h) equal bins); merged to
    plot_bins bins when len(h) is a multiple of it."""
    pw, ph, ml, mr, mt, mb = 420, 300, 60, 25, 40, 45
    legend_h = 16 * len(series) + 10
    width = len(panels) * (pw + ml + mr)
    height = ph + mt + mb + legend_h
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
           f'font-family="sans-serif" font-size="11">',
           f'<rect width="{width}" height="{height}" fill="white"/>',
           f'<text x="{width / 2}" y="18" text-anchor="middle" font-size="13">{_esc(title)}</text>']
    for p, (lo, hi) in enumerate(panels):
        x0 = p * (pw + ml + mr) + ml
        y0 = mt
        # Percentages per bin within the panel range.
        lines = []
        ymax = 0.0
        for label, h in series:
            h = np.asarray(h, dtype=float)
            if plot_bins and len(h) > plot_bins and len(h) % plot_bins == 0:
                h = h.reshape(plot_bins, -1).sum(axis=1)
            if h.sum() == 0:
                lines.append([])
                continue
            nb = len(h)
            pct = 100.0 * h / h.sum()
            pts = [((k + 0.5) / nb, pct[k]) for k in range(nb) if lo - 1e-12 <= (k + 0.5) / nb <= hi + 1e-12]
            ymax = max([ymax] + [y for _, y in pts])
            lines.append(pts)
        ymax = ymax * 1.05 if ymax > 0 else 1.0
        # Nice tick step.
        step = 10 ** math.floor(math.log10(ymax / 4)) if ymax > 0 else 1
        for m in (1, 2, 5, 10):
            if ymax / (step * m) <= 6:
                step *= m
                break
        out.append(f'<rect x="{x0}" y="{y0}" width="{pw}" height="{ph}" fill="none" stroke="#444"/>')
        X = lambda x: x0 + (x - lo) / (hi - lo) * pw  # noqa: E731
        Y = lambda y: y0 + ph - y / ymax * ph  # noqa: E731
        t = 0.0
        while t <= ymax + 1e-12:
            out.append(f'<line x1="{x0}" y1="{Y(t):.1f}" x2="{x0 + pw}" y2="{Y(t):.1f}" stroke="#eee"/>')
            out.append(f'<text x="{x0 - 4}" y="{Y(t) + 4:.1f}" text-anchor="end">{t:g}</text>')
            t += step
        nx = 6 if hi - lo > 0.45 else 4
        for k in range(nx + 1):
            x = lo + (hi - lo) * k / nx
            out.append(f'<text x="{X(x):.1f}" y="{y0 + ph + 15}" text-anchor="middle">{x:.2f}</text>')
        out.append(f'<text x="{x0 + pw / 2}" y="{y0 + ph + 32}" text-anchor="middle">'
                   f'{_esc(xlabel)} in [{lo}, {hi}]</text>')
        out.append(f'<text x="{x0 - 42}" y="{y0 + ph / 2}" text-anchor="middle" '
                   f'transform="rotate(-90 {x0 - 42} {y0 + ph / 2})">% of elements per bin</text>')
        for s, pts in enumerate(lines):
            if not pts:
                continue
            color = PALETTE[s % len(PALETTE)]
            dash = ' stroke-dasharray="5,3"' if s >= len(PALETTE) else ""
            d = " ".join(f"{X(x):.1f},{Y(y):.1f}" for x, y in pts)
            out.append(f'<polyline points="{d}" fill="none" stroke="{color}" stroke-width="1.5"{dash}/>')
    # Legend.
    ly = mt + ph + mb
    for s, (label, _) in enumerate(series):
        color = PALETTE[s % len(PALETTE)]
        y = ly + 14 * s + 10
        out.append(f'<line x1="{ml}" y1="{y - 4}" x2="{ml + 24}" y2="{y - 4}" stroke="{color}" stroke-width="2"/>')
        out.append(f'<text x="{ml + 30}" y="{y}">{_esc(label)}</text>')
    out.append("</svg>")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")
