#!/usr/bin/python3
"""Every surface format gives the same analysis as the STL it came from.

For each *.stl in --data (default ../shared/data/vascular, read in place),
the surface is converted with VTK's own writers (python3-vtk9) to VTK XML
PolyData (appended raw + zlib, and ascii) and legacy VTK (binary and ascii,
the 5.1 and the classic 4.2 cell layouts), with short own writers to OBJ and
PLY (ascii and binary little endian), and gzip-compressed (.stl.gz,
.vtp.gz). `vesselmesh info --json` runs on the original and on each copy;
the counts vertices, triangles, components, len(openings), genus and closed
must equal the STL's. Each *.vtp in --data is checked the same way against
its own analysis (copies written by VTK from VTK's reading of it), and its
triangle count against VTK's.

One conversion loses data: VTK's legacy ASCII writer prints coordinates
with 6 significant digits (%g), which can merge nearly coincident vertices.
For those files the reference is VTK's own reading of the written file
(vtkPolyDataReader, re-saved losslessly as binary .vtp), and the line says
how the counts differ from the original's.

Prints one line per check; exits 1 if any fails.
Usage: validation/format_roundtrip.py [--data DIR] [--vesselmesh PATH] [--keep DIR]
"""

import argparse
import gzip
import json
import pathlib
import shutil
import struct
import subprocess
import sys
import tempfile

from vtkmodules.util import numpy_support
from vtkmodules.vtkCommonCore import vtkIdList
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkIOGeometry import vtkSTLReader
from vtkmodules.vtkIOLegacy import vtkPolyDataReader, vtkPolyDataWriter
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader, vtkXMLPolyDataWriter

ROOT = pathlib.Path(__file__).resolve().parent.parent
KEYS = ("vertices", "triangles", "components", "openings", "genus", "closed")


def analysis(vesselmesh, path):
    """The compared counts of `vesselmesh info --json path`, or an error string."""
    run = subprocess.run([str(vesselmesh), "info", "--json", str(path)],
                         capture_output=True, text=True, check=False)
    if run.returncode != 0:
        return None, run.stderr.strip()
    d = json.loads(run.stdout)
    counts = {k: d[k] for k in KEYS if k != "openings"}
    counts["openings"] = len(d["openings"])
    return counts, d["format"]


def triangles_of(poly):
    """Point array (n, 3) and the polygons' point lists of a vtkPolyData."""
    pts = numpy_support.vtk_to_numpy(poly.GetPoints().GetData())
    cells = []
    ids = poly.GetPolys()
    ids.InitTraversal()
    lst = vtkIdList()
    while ids.GetNextCell(lst):
        cells.append([lst.GetId(i) for i in range(lst.GetNumberOfIds())])
    return pts, cells


def write_obj(poly, path):
    pts, cells = triangles_of(poly)
    with open(path, "w") as f:
        f.write("# written by format_roundtrip.py\no surface\n")
        for p in pts:
            f.write("v %.17g %.17g %.17g\n" % (p[0], p[1], p[2]))
        for c in cells:
            f.write("f " + " ".join(str(i + 1) for i in c) + "\n")


def write_ply(poly, path, binary):
    pts, cells = triangles_of(poly)
    double = pts.dtype.itemsize == 8
    kind = "double" if double else "float"
    header = ("ply\nformat %s 1.0\ncomment written by format_roundtrip.py\n"
              "element vertex %d\nproperty %s x\nproperty %s y\nproperty %s z\n"
              "element face %d\nproperty list uchar int vertex_indices\nend_header\n"
              % ("binary_little_endian" if binary else "ascii", len(pts), kind, kind, kind,
                 len(cells)))
    with open(path, "wb") as f:
        f.write(header.encode())
        if binary:
            fmt = "<3d" if double else "<3f"
            f.write(b"".join(struct.pack(fmt, *p) for p in pts))
            f.write(b"".join(struct.pack("<B%di" % len(c), len(c), *c) for c in cells))
        else:
            for p in pts:
                f.write(("%.17g %.17g %.17g\n" % (p[0], p[1], p[2])).encode())
            for c in cells:
                f.write((str(len(c)) + " " + " ".join(map(str, c)) + "\n").encode())


def write_vtp(poly, path, ascii_mode):
    w = vtkXMLPolyDataWriter()
    w.SetInputData(poly)
    w.SetFileName(str(path))
    if ascii_mode:
        w.SetDataModeToAscii()
    else:
        w.SetDataModeToAppended()
        w.EncodeAppendedDataOff()  # raw binary
        w.SetCompressorTypeToZLib()
    if not w.Write():
        raise RuntimeError("VTK could not write " + str(path))


def write_vtk(poly, path, binary, version):
    w = vtkPolyDataWriter()
    w.SetInputData(poly)
    w.SetFileName(str(path))
    w.SetFileVersion(version)
    if binary:
        w.SetFileTypeToBinary()
    else:
        w.SetFileTypeToASCII()
    if not w.Write():
        raise RuntimeError("VTK could not write " + str(path))


def vtk_reading(vesselmesh, path, out):
    """Counts of the surface VTK itself reads from a legacy file (re-saved as
    binary appended .vtp, lossless, then analysed)."""
    reader = vtkPolyDataReader()
    reader.SetFileName(str(path))
    reader.Update()
    copy = out / (path.stem + "-as-read-by-vtk.vtp")
    write_vtp(reader.GetOutput(), copy, False)
    counts, _ = analysis(vesselmesh, copy)
    return counts


def gzip_copy(src, dst):
    with open(src, "rb") as f, gzip.open(dst, "wb") as g:
        shutil.copyfileobj(f, g)


def conversions(poly, src, out, stem):
    """Writes every copy of `poly` into `out`; returns [(label, path)]."""
    made = []

    def add(label, name, fn):
        path = out / (stem + name)
        fn(path)
        made.append((label, path))

    add("vtp (appended raw, zlib)", ".vtp", lambda p: write_vtp(poly, p, False))
    add("vtp (ascii)", "-ascii.vtp", lambda p: write_vtp(poly, p, True))
    add("vtk 5.1 (binary)", ".vtk", lambda p: write_vtk(poly, p, True, 51))
    add("vtk 5.1 (ascii)", "-ascii.vtk", lambda p: write_vtk(poly, p, False, 51))
    add("vtk 4.2 (binary)", "-42.vtk", lambda p: write_vtk(poly, p, True, 42))
    add("vtk 4.2 (ascii)", "-42-ascii.vtk", lambda p: write_vtk(poly, p, False, 42))
    add("obj", ".obj", lambda p: write_obj(poly, p))
    add("ply (ascii)", "-ascii.ply", lambda p: write_ply(poly, p, False))
    add("ply (binary little endian)", ".ply", lambda p: write_ply(poly, p, True))
    add("vtp.gz", ".vtp.gz", lambda p: gzip_copy(out / (stem + ".vtp"), p))
    if src.suffix == ".stl":
        add("stl.gz", ".stl.gz", lambda p: gzip_copy(src, p))
    else:
        add("original.gz", src.suffix + ".gz", lambda p: gzip_copy(src, p))
    return made


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--data", default=str(ROOT / "../shared/data/vascular"))
    ap.add_argument("--vesselmesh", default=str(ROOT / "build/vesselmesh"))
    ap.add_argument("--keep", help="write the converted files here and keep them")
    args = ap.parse_args()
    data = pathlib.Path(args.data)
    vesselmesh = pathlib.Path(args.vesselmesh)
    if not vesselmesh.exists():
        print("no vesselmesh at %s (build it first)" % vesselmesh)
        return 1
    inputs = sorted(data.glob("*.stl")) + sorted(data.glob("*.vtp"))
    if not inputs:
        print("no *.stl or *.vtp in %s" % data)
        return 1
    failures = checks = 0
    tmp = None
    if args.keep:
        out = pathlib.Path(args.keep)
        out.mkdir(parents=True, exist_ok=True)
    else:
        tmp = tempfile.TemporaryDirectory(prefix="format_roundtrip_")
        out = pathlib.Path(tmp.name)
    for src in inputs:
        ref, ref_format = analysis(vesselmesh, src)
        if ref is None:
            print("FAIL %s: vesselmesh info failed: %s" % (src.name, ref_format))
            failures += 1
            continue
        if src.suffix == ".stl":
            reader = vtkSTLReader()  # merges identical points, as a VTK user gets it
        else:
            reader = vtkXMLPolyDataReader()
        reader.SetFileName(str(src))
        reader.Update()
        poly = vtkPolyData()
        poly.DeepCopy(reader.GetOutput())
        print("%s: %s, %s" % (src.name, ref_format,
                               ", ".join("%s %s" % (k, ref[k]) for k in KEYS)))
        if src.suffix == ".vtp":
            # The VTP reader against VTK's own: same number of triangles.
            checks += 1
            run = subprocess.run([str(vesselmesh), "info", "--json", str(src)],
                                 capture_output=True, text=True, check=False)
            ours = json.loads(run.stdout)["input_triangles"]
            vtk_tris = sum(max(c.GetNumberOfPoints() - 2, 0) for c in
                           (poly.GetCell(i) for i in range(poly.GetNumberOfCells()))
                           if c.GetCellType() in (5, 7, 9))
            ok = ours == vtk_tris
            failures += not ok
            print("  %s %-30s input triangles %d, VTK reads %d" %
                  ("PASS" if ok else "FAIL", "vtp vs VTK's reader", ours, vtk_tris))
        for label, path in conversions(poly, src, out, src.stem):
            checks += 1
            got, fmt = analysis(vesselmesh, path)
            if got is None:
                failures += 1
                print("  FAIL %-30s %s" % (label, fmt))
                continue
            want, note = ref, ""
            if label.startswith("vtk") and "(ascii)" in label:
                want = vtk_reading(vesselmesh, path, out)
                lost = [k for k in KEYS if want[k] != ref[k]]
                note = " = VTK's own reading of the file" + (
                    " (6-digit ASCII lost precision: %s)" % ", ".join(
                        "%s %s vs %s in the original" % (k, want[k], ref[k]) for k in lost)
                    if lost else "")
            diff = [k for k in KEYS if got[k] != want[k]]
            if diff:
                failures += 1
                print("  FAIL %-30s %s" % (label, ", ".join(
                    "%s %s != %s" % (k, got[k], want[k]) for k in diff)))
            else:
                print("  PASS %-30s read as %s%s" % (label, fmt, note))
    if tmp:
        tmp.cleanup()
    print("%d checks, %d failed" % (checks, failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
