#!/usr/bin/python3
"""Independent check of vesselmesh's VTK outputs against its MSH file.

Reads the files with VTK's own XML readers (Debian python3-vtk9) and meshio
(python3-meshio), the MSH with meshio, and checks that they describe the
same mesh:

  --vtu FILE.vtu            the volume: VTK reads it without error; only
                            tetrahedra (10) and wedges (13); per ModelRegionID
                            as many of each as the MSH's physical volume of
                            that tag; every cell volume positive
                            (vtkCellSizeFilter) and every wedge's first
                            triangle facing away from its second (VTK's
                            convention); GlobalNodeID in range and at the
                            MSH node's coordinates; GlobalElementID 1..n;
                            meshio reads the same cells and points.
  --vtp FILE.vtp            an exterior surface (mesh-complete.exterior.vtp):
                            per ModelFaceID the same faces as the MSH's
                            physical surface of that tag that are a face of
                            exactly one MSH volume element (computed here
                            from the MSH's elements), oriented outward of
                            it; GlobalNodeID in range and at the MSH node's
                            coordinates; with --vtu, each GlobalElementID
                            names a VTU cell having the face.
  --mesh-complete DIR|ZIP   SimVascular's mesh-complete layout: the zip is
                            tested (CRCs), then the VTU and the exterior VTP
                            as above, every mesh-surfaces/<name>.vtp holding
                            exactly the MSH's faces of that physical name,
                            and mesh-complete.names.json agreeing with the
                            MSH's physical names, tags and counts.

Face id = MSH physical tag, region id = MSH physical volume tag (vesselmesh
numbers the surface groups 1..k and the volume groups k+1.., unique across
dimensions, the same numbers in every file); names.json must give the same
names.
Prints one line per check (PASS/FAIL), exits 1 when any check fails.

Usage: /usr/bin/python3 validation/check_vtk_outputs.py --msh out.msh
           [--vtu out.vtu] [--vtp out.vtp] [--mesh-complete out.zip]
"""
import argparse
import contextlib
import io
import json
import os
import sys
import tempfile
import zipfile
from collections import Counter

import meshio
import numpy as np
import vtk
from vtk.util import numpy_support

VTK_TRIANGLE, VTK_QUAD, VTK_TETRA, VTK_WEDGE = 5, 9, 10, 13

failures = 0


def report(ok, name, detail=""):
    global failures
    if not ok:
        failures += 1
    print(f"{'PASS' if ok else 'FAIL'} {name}" + (f": {detail}" if detail else ""))
    return ok


# ---- MSH ---------------------------------------------------------------------

class Msh:
    """The MSH's points, volume elements and faces by physical tag."""

    def __init__(self, path):
        with contextlib.redirect_stdout(io.StringIO()):  # meshio's gmsh reader prints a newline
            m = meshio.read(path)
        self.points = np.asarray(m.points, dtype=float)
        self.names = {}  # (dim, tag) -> name
        for name, (tag, dim) in m.field_data.items():
            self.names[(int(dim), int(tag))] = name
        phys = m.cell_data["gmsh:physical"]
        self.volume = {"tetra": Counter(), "wedge": Counter()}  # tag -> count
        self.faces = {}  # tag -> list of sorted node tuples
        elems = []  # node lists of the volume elements (for face uses)
        for block, tags in zip(m.cells, phys):
            data = np.asarray(block.data)
            if block.type in ("tetra", "wedge"):
                self.volume[block.type].update(int(t) for t in tags)
                elems.append((block.type, data))
            elif block.type in ("triangle", "quad"):
                for tag, nodes in zip(tags, data):
                    self.faces.setdefault(int(tag), []).append(tuple(sorted(nodes)))
            else:
                raise SystemExit(f"unexpected MSH cell type {block.type}")
        self.face_uses = face_uses(elems)

    def surface_tags(self):
        return sorted(t for (d, t) in self.names if d == 2)

    def volume_tags(self):
        return sorted(t for (d, t) in self.names if d == 3)


def element_faces(kind, data):
    """The faces of MSH elements of one kind (tetra or wedge, Gmsh node
    order) as lists of (elements x 3) and (elements x 4) node arrays; only
    their vertex sets are used."""
    if kind == "tetra":
        tri = [data[:, [0, 1, 2]], data[:, [0, 1, 3]], data[:, [0, 2, 3]], data[:, [1, 2, 3]]]
        quad = []
    else:  # wedge: triangles (0,1,2), (3,4,5); quads by vertex set
        tri = [data[:, [0, 1, 2]], data[:, [3, 4, 5]]]
        quad = [data[:, [0, 1, 4, 3]], data[:, [1, 2, 5, 4]], data[:, [2, 0, 3, 5]]]
    return tri, quad


def face_uses(elems):
    """{sorted node tuple: number of volume elements having that face}."""
    tris, quads = [], []
    for kind, data in elems:
        t, q = element_faces(kind, data)
        tris += t
        quads += q
    uses = {}
    for arrays in (tris, quads):
        if not arrays:
            continue
        a = np.sort(np.concatenate(arrays), axis=1)
        keys, counts = np.unique(a, axis=0, return_counts=True)
        for k, c in zip(map(tuple, keys.tolist()), counts.tolist()):
            uses[k] = c
    return uses


# ---- VTK readers -------------------------------------------------------------

class ErrorCatcher:
    def __init__(self):
        self.messages = []

    def __call__(self, obj, event):
        self.messages.append(event)


def vtk_read(reader_class, path):
    reader = reader_class()
    catcher = ErrorCatcher()
    reader.AddObserver("ErrorEvent", catcher)
    reader.GetExecutive().AddObserver("ErrorEvent", catcher)
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput(), catcher.messages


def array(data, name):
    a = data.GetArray(name)
    return None if a is None else numpy_support.vtk_to_numpy(a)


def cells_of(ds):
    """(types, list of node-id arrays) of a vtkUnstructuredGrid/vtkPolyData."""
    n = ds.GetNumberOfCells()
    types = np.array([ds.GetCellType(i) for i in range(n)], dtype=np.int64)
    ids = vtk.vtkIdList()
    cells = []
    for i in range(n):
        ds.GetCellPoints(i, ids)
        cells.append(np.array([ids.GetId(k) for k in range(ids.GetNumberOfIds())], dtype=np.int64))
    return types, cells


# ---- checks ------------------------------------------------------------------

def check_global_nodes(label, ds, msh):
    pts = numpy_support.vtk_to_numpy(ds.GetPoints().GetData()).astype(float)
    gid = array(ds.GetPointData(), "GlobalNodeID")
    if not report(gid is not None and len(gid) == len(pts), f"{label}: GlobalNodeID per point"):
        return None
    in_range = gid.min() >= 1 and gid.max() <= len(msh.points)
    report(in_range, f"{label}: GlobalNodeID in 1..{len(msh.points)}",
           f"range {gid.min()}..{gid.max()}")
    if not in_range:
        return None
    err = float(np.abs(msh.points[gid - 1] - pts).max()) if len(pts) else 0.0
    report(err == 0.0, f"{label}: points at their MSH node's coordinates", f"max difference {err:g}")
    return gid - 1  # the MSH node index of each point


class Vtu:
    def __init__(self, path, msh):
        label = os.path.basename(path)
        self.grid, errors = vtk_read(vtk.vtkXMLUnstructuredGridReader, path)
        self.cells, self.msh_node = [], None
        if not report(not errors and self.grid.GetNumberOfCells() > 0,
                      f"{label}: vtkXMLUnstructuredGridReader reads it",
                      f"{self.grid.GetNumberOfPoints()} points, {self.grid.GetNumberOfCells()} cells"
                      + (f", {len(errors)} errors" if errors else "")):
            return
        self.types, self.cells = cells_of(self.grid)
        other = set(np.unique(self.types).tolist()) - {VTK_TETRA, VTK_WEDGE}
        report(not other, f"{label}: cells are tetrahedra and wedges only",
               f"{int((self.types == VTK_TETRA).sum())} tetra, "
               f"{int((self.types == VTK_WEDGE).sum())} wedge" + (f", other {other}" if other else ""))
        region = array(self.grid.GetCellData(), "ModelRegionID")
        if report(region is not None, f"{label}: ModelRegionID present"):
            for kind, code in (("tetra", VTK_TETRA), ("wedge", VTK_WEDGE)):
                got = Counter(region[self.types == code].tolist())
                want = msh.volume[kind]
                report(got == want, f"{label}: {kind} per region = MSH physical volumes",
                       ", ".join(f"{msh.names.get((3, t), t)}:{n}" for t, n in sorted(want.items()))
                       + ("" if got == want else f" but VTU has {dict(got)}"))
        gel = array(self.grid.GetCellData(), "GlobalElementID")
        n = self.grid.GetNumberOfCells()
        report(gel is not None and np.array_equal(gel, np.arange(1, n + 1)),
               f"{label}: GlobalElementID = 1..{n}")
        self.msh_node = check_global_nodes(label, self.grid, msh)
        # Volumes: VTK's own integration; wedges also by VTK's convention
        # (first triangle's normal away from the second).
        f = vtk.vtkCellSizeFilter()
        f.SetInputData(self.grid)
        f.ComputeVertexCountOff()
        f.ComputeLengthOff()
        f.ComputeAreaOff()
        f.Update()
        vol = array(f.GetOutput().GetCellData(), "Volume")
        report(vol is not None and vol.min() > 0, f"{label}: every cell volume > 0 (vtkCellSizeFilter)",
               f"min {vol.min():.3g}, total {vol.sum():.6g}")
        pts = numpy_support.vtk_to_numpy(self.grid.GetPoints().GetData()).astype(float)
        wedges = np.array([c for c, t in zip(self.cells, self.types) if t == VTK_WEDGE]).reshape(-1, 6)
        if len(wedges):
            p = pts[wedges]
            n1 = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
            away = np.einsum("ij,ij->i", n1, p[:, 3:].mean(axis=1) - p[:, :3].mean(axis=1))
            report(bool((away < 0).all()), f"{label}: wedges' first triangle faces away from the second",
                   f"{int((away >= 0).sum())} of {len(wedges)} wrong")
        # meshio, a second reader.
        mm = meshio.read(path)
        got = {c.type: len(c.data) for c in mm.cells}
        want = {"tetra": int((self.types == VTK_TETRA).sum()), "wedge": int((self.types == VTK_WEDGE).sum())}
        want = {k: v for k, v in want.items() if v}
        same_points = np.array_equal(np.asarray(mm.points, dtype=float), pts)
        report(got == want and same_points, f"{label}: meshio reads the same cells and points", str(got))

    def element_has(self, element, nodes):
        return set(nodes) <= set(self.cells[element].tolist())


def check_surface(label, path, msh, expected, vtu, face_id=None):
    """A VTP whose faces must be `expected`: {tag: set of sorted MSH node
    tuples}. Returns the VTP's faces by tag."""
    poly, errors = vtk_read(vtk.vtkXMLPolyDataReader, path)
    if not report(not errors and poly.GetNumberOfPolys() == poly.GetNumberOfCells() > 0,
                  f"{label}: vtkXMLPolyDataReader reads it",
                  f"{poly.GetNumberOfPoints()} points, {poly.GetNumberOfPolys()} polys"
                  + (f", {len(errors)} errors" if errors else "")):
        return
    types, cells = cells_of(poly)
    report(set(types.tolist()) <= {VTK_TRIANGLE, VTK_QUAD}, f"{label}: polys are triangles and quads")
    node = check_global_nodes(label, poly, msh)
    fid = array(poly.GetCellData(), "ModelFaceID")
    if not report(fid is not None and len(fid) == len(cells), f"{label}: ModelFaceID per cell"):
        return
    if node is None:
        return
    if face_id is not None:
        report(bool((fid == face_id).all()), f"{label}: ModelFaceID = {face_id} throughout")
    got = {}
    for f, c in zip(fid.tolist(), cells):
        got.setdefault(f, []).append(tuple(sorted(node[c].tolist())))
    for tag in sorted(set(got) | set(expected)):
        g, w = got.get(tag, []), expected.get(tag, set())
        name = msh.names.get((2, tag), f"tag {tag}")
        ok = len(g) == len(w) and set(g) == w
        report(ok, f"{label}: face id {tag} ({name}) = the MSH's faces", f"{len(g)} cells"
               + ("" if ok else f", MSH {len(w)}, {len(set(g) - w)} not in MSH, {len(w - set(g))} missing"))
    # Each face oriented outward of the element it names (needs the VTU).
    gel = array(poly.GetCellData(), "GlobalElementID")
    if vtu is None or vtu.msh_node is None:
        return
    if not report(gel is not None and len(gel) == len(cells), f"{label}: GlobalElementID per cell"):
        return
    vtu_node = vtu.msh_node
    pts = msh.points
    bad_elem, inward = 0, 0
    by_shape = {}  # (face size, element size): (faces' nodes, elements' nodes)
    for c, e in zip(cells, gel.tolist()):
        nodes = node[c]
        if not (1 <= e <= len(vtu.cells)):
            bad_elem += 1
            continue
        elem = vtu_node[vtu.cells[e - 1]]
        if not set(nodes.tolist()) <= set(elem.tolist()):
            bad_elem += 1
            continue
        faces, elems = by_shape.setdefault((len(nodes), len(elem)), ([], []))
        faces.append(nodes)
        elems.append(elem)
    for (n, _), (faces, elems) in by_shape.items():
        p = pts[np.array(faces)]
        normal = sum(np.cross(p[:, k], p[:, (k + 1) % n]) for k in range(n))  # Newell's
        towards = pts[np.array(elems)].mean(axis=1) - p.mean(axis=1)
        inward += int((np.einsum("ij,ij->i", normal, towards) >= 0).sum())
    report(bad_elem == 0, f"{label}: each GlobalElementID is a VTU cell having the face",
           f"{bad_elem} of {len(cells)} wrong")
    report(inward == 0, f"{label}: faces oriented outward of that cell", f"{inward} of {len(cells)} inward")


def exterior_expected(msh):
    return {tag: {f for f in faces if msh.face_uses.get(f, 0) == 1} for tag, faces in msh.faces.items()
            if any(msh.face_uses.get(f, 0) == 1 for f in faces)}


def check_mesh_complete(path, msh):
    tmp = None
    if zipfile.is_zipfile(path):
        with zipfile.ZipFile(path) as z:
            bad = z.testzip()
            report(bad is None, f"{os.path.basename(path)}: zip CRCs", f"{len(z.namelist())} entries")
            tmp = tempfile.TemporaryDirectory()
            z.extractall(tmp.name)
            root = tmp.name
    else:
        root = path
    need = ["mesh-complete.mesh.vtu", "mesh-complete.exterior.vtp", "mesh-complete.names.json"]
    missing = [f for f in need if not os.path.exists(os.path.join(root, f))]
    if not report(not missing, "mesh-complete: layout", "missing " + ", ".join(missing) if missing else
                  ", ".join(need + ["mesh-surfaces/"])):
        return
    with open(os.path.join(root, "mesh-complete.names.json")) as f:
        names = json.load(f)
    faces = {d["id"]: d for d in names["faces"]}
    regions = {d["id"]: d for d in names["regions"]}
    want_faces = {t: msh.names[(2, t)] for t in msh.surface_tags() if t in msh.faces}
    got_faces = {i: d["name"] for i, d in faces.items()}
    report(got_faces == want_faces, "names.json: face ids and names = MSH physical surfaces", str(got_faces))
    counts_ok = all(d["triangles"] + d["quads"] == len(msh.faces.get(i, [])) for i, d in faces.items())
    report(counts_ok, "names.json: face counts = MSH")
    ext = exterior_expected(msh)
    ext_ok = all(d["exterior"] == (i in ext and len(ext[i]) == len(msh.faces[i])) for i, d in faces.items())
    report(ext_ok, "names.json: exterior flags", ", ".join(f"{d['name']}:{d['exterior']}" for d in faces.values()))
    want_regions = {t: msh.names[(3, t)] for t in msh.volume_tags()}
    report({i: d["name"] for i, d in regions.items()} == want_regions,
           "names.json: region ids and names = MSH physical volumes", str(want_regions))
    report(all(d["elements"] == msh.volume["tetra"][i] + msh.volume["wedge"][i] for i, d in regions.items()),
           "names.json: region element counts = MSH")
    report(bool(names.get("provenance")), "names.json: provenance", names.get("provenance", ""))
    vtu = Vtu(os.path.join(root, "mesh-complete.mesh.vtu"), msh)
    check_surface("mesh-complete.exterior.vtp", os.path.join(root, "mesh-complete.exterior.vtp"), msh, ext, vtu)
    for i, d in sorted(faces.items()):
        p = os.path.join(root, d["file"])
        if report(os.path.exists(p), f"{d['file']}: present"):
            check_surface(d["file"], p, msh, {i: set(msh.faces.get(i, []))}, vtu, face_id=i)
    if tmp:
        tmp.cleanup()


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--msh", required=True)
    ap.add_argument("--vtu")
    ap.add_argument("--vtp")
    ap.add_argument("--mesh-complete")
    a = ap.parse_args()
    if not (a.vtu or a.vtp or a.mesh_complete):
        ap.error("give --vtu, --vtp and/or --mesh-complete")
    msh = Msh(a.msh)
    print(f"MSH {a.msh}: {len(msh.points)} nodes, "
          + ", ".join(f"{k} {sum(c.values())}" for k, c in msh.volume.items())
          + f", {sum(len(f) for f in msh.faces.values())} faces in {len(msh.faces)} physical surfaces")
    vtu = Vtu(a.vtu, msh) if a.vtu else None
    if a.vtp:
        check_surface(os.path.basename(a.vtp), a.vtp, msh, exterior_expected(msh), vtu)
    if a.mesh_complete:
        check_mesh_complete(a.mesh_complete, msh)
    print(f"{'FAILED' if failures else 'OK'}: {failures} check(s) failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
