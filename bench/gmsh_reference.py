#!/usr/bin/env python3
"""Gmsh's own STL remeshing pipeline at a uniform size h, as the reference
vesselmesh is compared with (issue 3, and the volume issue after it).

  merge STL -> classifySurfaces(angle, boundary=True, forReparametrization=True,
  curveAngle) -> createGeometry -> Mesh.MeshSizeMin = Mesh.MeshSizeMax = h,
  Mesh.Algorithm = 6 (Frontal-Delaunay) -> generate(2)
  [--volume: every boundary curve loop (opening) capped by a plane surface,
   surface loop -> volume, Mesh.Algorithm3D = 10 (HXT) -> generate(3)]

One thread by default; --threads T sets General.NumThreads and
Mesh.MaxNumThreads1D/2D/3D to T (Gmsh 4.8 with OpenMP: the surface mesh runs
its patches on the threads, HXT its volume). Wall time per stage, CPU time of
the process (all its threads) per stage. Quality computed here from node coordinates with the seed's
formulas (validation/meshquality.py), the same measure as vesselmesh's report:
gamma_k over the triangles of the input surface's patches (caps excluded),
gamma_t over the tetrahedra. Gmsh 4.8's Python API has no
getElementQualities; with a newer Gmsh its 'gamma' is reported beside ours
for reference (`gmsh_gamma_k`, `gmsh_gamma_t` keys).

usage: gmsh_reference.py FILE.stl --size H [--volume] [--threads 1] [--angle 40]
                         [--curve-angle 180] [--json OUT.json] [--msh OUT.msh]
As a module: run(path, h, volume=False, threads=1, ...) -> dict.
"""
import argparse
import json
import math
import os
import resource
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
# The quality measures live with the validation (validation/meshquality.py).
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "validation"))
import meshquality  # noqa: E402

DEFAULT_ANGLE = 40.0
DEFAULT_CURVE_ANGLE = 180.0


class _Stage:
    """Times one stage: wall clock into res['seconds'][name], CPU time of
    the process into res['cpu_seconds'][name] (less sensitive to a loaded
    machine than wall time; the sum over Gmsh's threads)."""

    def __init__(self, res, name):
        self.res, self.name = res, name

    def __enter__(self):
        self.wall, self.cpu = time.perf_counter(), time.process_time()

    def __exit__(self, *exc):
        if exc[0] is None:
            self.res["seconds"][self.name] = time.perf_counter() - self.wall
            self.res["cpu_seconds"][self.name] = time.process_time() - self.cpu


def _open_loops(gmsh, surfaces):
    """Curve loops bounding exactly one surface (the openings), as lists of
    curve tags grouped by shared end points."""
    count = {}
    for s in surfaces:
        for dim, c in gmsh.model.getBoundary([(2, s)], oriented=False):
            count[abs(c)] = count.get(abs(c), 0) + 1
    free = [c for c, n in count.items() if n == 1]
    # Union-find over end points.
    parent = {c: c for c in free}

    def find(x):
        while parent[x] != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x

    by_point = {}
    for c in free:
        for _, p in gmsh.model.getBoundary([(1, c)], oriented=False):
            by_point.setdefault(abs(p), []).append(c)
    for cs in by_point.values():
        for c in cs[1:]:
            parent[find(c)] = find(cs[0])
    loops = {}
    for c in free:
        loops.setdefault(find(c), []).append(c)
    return list(loops.values())


def _ordered_loop(gmsh, curves):
    """Orders (and signs) the curves of one loop head to tail, as
    geo.addCurveLoop wants them."""
    ends = {}
    for c in curves:
        b = gmsh.model.getBoundary([(1, c)], oriented=True)
        pts = [abs(t) for _, t in b]
        ends[c] = (pts[0], pts[-1]) if pts else (None, None)
    if len(curves) == 1:
        return list(curves)
    left = list(curves)
    first = left.pop(0)
    out = [first]
    cur = ends[first][1]
    while left:
        for i, c in enumerate(left):
            a, b = ends[c]
            if a == cur:
                out.append(c)
                cur = b
                left.pop(i)
                break
            if b == cur:
                out.append(-c)
                cur = a
                left.pop(i)
                break
        else:
            raise RuntimeError("open boundary curves do not form a loop")
    return out


def _collect(gmsh, dim, tags):
    """Node coordinates (dict-free numpy) and element connectivity of the
    given entities, element type 2 (dim 2) or 4 (dim 3)."""
    import numpy as np
    ntags, coords, _ = gmsh.model.mesh.getNodes()
    xyz = np.zeros((int(ntags.max()) + 1, 3))
    xyz[ntags.astype(np.int64)] = coords.reshape(-1, 3)
    etype = 2 if dim == 2 else 4
    k = 3 if dim == 2 else 4
    conn, etags = [], []
    for t in tags:
        types, el, nodes = gmsh.model.mesh.getElements(dim, t)
        for ty, e, n in zip(types, el, nodes):
            if ty == etype:
                conn.append(np.asarray(n, dtype=np.int64).reshape(-1, k))
                etags.append(np.asarray(e, dtype=np.int64))
    conn = np.concatenate(conn) if conn else np.zeros((0, k), np.int64)
    etags = np.concatenate(etags) if etags else np.zeros(0, np.int64)
    return xyz, conn, etags


def run(path, h, volume=False, angle=DEFAULT_ANGLE, curve_angle=DEFAULT_CURVE_ANGLE,
        msh_out=None, verbose=False, threads=1):
    """Runs Gmsh's pipeline on `path` at uniform size h; returns a dict
    (see the module doc). Never raises for a Gmsh failure: the dict then has
    ok False and error."""
    import gmsh
    import numpy as np
    res = dict(file=os.path.basename(path), h=h, volume=volume, angle=angle,
               curve_angle=curve_angle, threads=threads, gmsh_version=None, ok=False, seconds={},
               cpu_seconds={})
    sec = res["seconds"]
    gmsh.initialize(["gmsh", "-nopopup"], readConfigFiles=False)
    try:
        res["gmsh_version"] = gmsh.option.getString("General.Version")
        gmsh.option.setNumber("General.Terminal", 1 if verbose else 0)
        gmsh.option.setNumber("General.Verbosity", 5 if verbose else 1)
        gmsh.option.setNumber("General.NumThreads", threads)
        for d in ("1D", "2D", "3D"):
            gmsh.option.setNumber(f"Mesh.MaxNumThreads{d}", threads)
        gmsh.model.add("ref")
        with _Stage(res, "merge"):
            gmsh.merge(path)

        with _Stage(res, "classify"):
            gmsh.model.mesh.classifySurfaces(angle * math.pi / 180.0, True, True,
                                             curve_angle * math.pi / 180.0)

        with _Stage(res, "create_geometry"):
            gmsh.model.mesh.createGeometry()
        walls = [t for _, t in gmsh.model.getEntities(2)]
        res["patches"] = len(walls)
        res["curves"] = len(gmsh.model.getEntities(1))

        caps = []
        if volume:
            with _Stage(res, "caps_volume_entities"):
                loops = _open_loops(gmsh, walls)
                res["openings"] = len(loops)
                for lp in loops:
                    cl = gmsh.model.geo.addCurveLoop(_ordered_loop(gmsh, lp))
                    caps.append(gmsh.model.geo.addPlaneSurface([cl]))
                sl = gmsh.model.geo.addSurfaceLoop(walls + caps)
                gmsh.model.geo.addVolume([sl])
                gmsh.model.geo.synchronize()

        gmsh.option.setNumber("Mesh.MeshSizeMin", h)
        gmsh.option.setNumber("Mesh.MeshSizeMax", h)
        gmsh.option.setNumber("Mesh.Algorithm", 6)
        gmsh.option.setNumber("Mesh.Algorithm3D", 10)

        with _Stage(res, "surface_mesh"):
            gmsh.model.mesh.generate(2)

        xyz, tri, tri_tags = _collect(gmsh, 2, walls)
        q = meshquality.gamma_k(xyz, tri)
        res["triangles"] = int(len(tri))
        res["gamma_k"] = meshquality.summary(q)
        res["median_edge"] = meshquality.median_edge(xyz, tri)
        if len(tri_tags) and hasattr(gmsh.model.mesh, "getElementQualities"):
            gq = np.asarray(gmsh.model.mesh.getElementQualities(tri_tags.tolist(), "gamma"))
            res["gmsh_gamma_k"] = dict(min=float(gq.min()), mean=float(gq.mean()),
                                       max_abs_diff_to_ours=float(np.abs(gq - q).max()))
        if caps:
            _, ctri, _ = _collect(gmsh, 2, caps)
            res["cap_triangles"] = int(len(ctri))

        if volume:
            with _Stage(res, "volume_mesh"):
                gmsh.model.mesh.generate(3)
            vols = [t for _, t in gmsh.model.getEntities(3)]
            xyz, tet, tet_tags = _collect(gmsh, 3, vols)
            res["tets"] = int(len(tet))
            res["nodes"] = int(len(gmsh.model.mesh.getNodes()[0]))
            res["gamma_t"] = meshquality.summary(meshquality.gamma_t(xyz, tet))
            res["median_tet_edge"] = meshquality.median_edge(xyz, tet)
            if len(tet):
                vol = meshquality.signed_tet_volumes(xyz, tet)
                res["inverted_tets"] = int(min((vol < 0).sum(), (vol > 0).sum()))
            if len(tet_tags) and hasattr(gmsh.model.mesh, "getElementQualities"):
                gq = np.asarray(gmsh.model.mesh.getElementQualities(tet_tags.tolist(), "gamma"))
                res["gmsh_gamma_t"] = dict(min=float(gq.min()), mean=float(gq.mean()))
            if res["tets"] == 0:
                raise RuntimeError("HXT produced no tetrahedra")
        else:
            res["nodes"] = int(len(gmsh.model.mesh.getNodes()[0]))
        for d in (sec, res["cpu_seconds"]):
            d["total"] = sum(v for k, v in d.items() if k != "total")
        if msh_out:
            gmsh.option.setNumber("Mesh.SaveAll", 1)
            gmsh.write(msh_out)
        res["ok"] = True
    except Exception as e:  # Gmsh raises plain Exceptions with its message
        res["error"] = str(e).strip() or type(e).__name__
    finally:
        gmsh.finalize()
    res["peak_rss_mb"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    return res


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("stl")
    ap.add_argument("--size", type=float, required=True, help="uniform mesh size h")
    ap.add_argument("--volume", action="store_true", help="cap openings, HXT volume")
    ap.add_argument("--threads", type=int, default=1,
                    help="General.NumThreads and Mesh.MaxNumThreads1D/2D/3D (default 1)")
    ap.add_argument("--angle", type=float, default=DEFAULT_ANGLE, help="classify angle, degrees")
    ap.add_argument("--curve-angle", type=float, default=DEFAULT_CURVE_ANGLE, help="degrees")
    ap.add_argument("--json", help="write the result here (default: stdout)")
    ap.add_argument("--msh", help="also write Gmsh's mesh")
    ap.add_argument("--verbose", action="store_true")
    a = ap.parse_args()
    r = run(a.stl, a.size, volume=a.volume, angle=a.angle, curve_angle=a.curve_angle,
            msh_out=a.msh, verbose=a.verbose, threads=a.threads)
    text = json.dumps(r, indent=1)
    if a.json:
        with open(a.json, "w") as f:
            f.write(text + "\n")
        s = r["seconds"]
        print(f"{r['file']} h={a.size}: " + ("ok" if r["ok"] else f"FAILED: {r.get('error')}") +
              (f", {r.get('triangles')} triangles, gamma_k min {r['gamma_k']['min']:.3f} "
               f"mean {r['gamma_k']['mean']:.4f}" if r.get("gamma_k") else "") +
              (f", {r.get('tets')} tets, gamma_t min {r['gamma_t']['min']:.3f} mean {r['gamma_t']['mean']:.3f}"
               if r.get("gamma_t") and r["gamma_t"]["count"] else "") +
              "; s: " + ", ".join(f"{k} {v:.2f}" for k, v in s.items()))
    else:
        print(text)
    return 0 if r["ok"] else 1


if __name__ == "__main__":
    sys.exit(main())
