#!/usr/bin/env python3
"""Writes the fuzzers' seed inputs into DIR: a small closed surface (an
octahedron) in every format and encoding the readers take, a few hostile
variants, and option texts for fuzz_options (first byte: the option's
index in the table, modulo its size).

Usage: make_seeds.py READERS_DIR OPTIONS_DIR
"""
import gzip
import struct
import sys
import zlib
from base64 import b64encode
from pathlib import Path

P = [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)]
T = [(0, 2, 4), (2, 1, 4), (1, 3, 4), (3, 0, 4), (2, 0, 5), (1, 2, 5), (3, 1, 5), (0, 3, 5)]


def stl_ascii(name="octa", eol="\n"):
    lines = [f"solid {name}"]
    for t in T:
        lines += ["facet normal 0 0 0", "outer loop"]
        lines += [f"vertex {P[v][0]} {P[v][1]} {P[v][2]}" for v in t]
        lines += ["endloop", "endfacet"]
    return (eol.join(lines + [f"endsolid {name}", ""])).encode()


def stl_binary():
    out = b"octahedron".ljust(80, b" ") + struct.pack("<I", len(T))
    for t in T:
        out += struct.pack("<3f", 0, 0, 0)
        for v in t:
            out += struct.pack("<3f", *P[v])
        out += b"\0\0"
    return out


def obj():
    return ("".join(f"v {x} {y} {z}\n" for x, y, z in P) + "g wall\n"
            + "".join(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in T)).encode()


def ply(binary):
    head = ("ply\nformat " + ("binary_little_endian" if binary else "ascii") + " 1.0\n"
            f"element vertex {len(P)}\nproperty float x\nproperty float y\nproperty float z\n"
            f"element face {len(T)}\nproperty list uchar int vertex_indices\nend_header\n")
    if not binary:
        return (head + "".join(f"{x} {y} {z}\n" for x, y, z in P)
                + "".join(f"3 {a} {b} {c}\n" for a, b, c in T)).encode()
    body = b"".join(struct.pack("<3f", *p) for p in P)
    body += b"".join(struct.pack("<B3i", 3, *t) for t in T)
    return head.encode() + body


def vtk_legacy():
    return ("# vtk DataFile Version 3.0\noctahedron\nASCII\nDATASET POLYDATA\n"
            f"POINTS {len(P)} float\n" + "".join(f"{x} {y} {z}\n" for x, y, z in P)
            + f"POLYGONS {len(T)} {4 * len(T)}\n" + "".join(f"3 {a} {b} {c}\n" for a, b, c in T)
            + f"CELL_DATA {len(T)}\nSCALARS ModelFaceID int 1\nLOOKUP_TABLE default\n"
            + "".join("1\n" for _ in T)).encode()


def vtp(encoding):
    pts = [x for p in P for x in p]
    conn = [v for t in T for v in t]
    offs = [3 * (i + 1) for i in range(len(T))]

    def array(kind, name, values, fmt, comps=1):
        attrs = f'type="{kind}" Name="{name}" NumberOfComponents="{comps}"'
        if encoding == "ascii":
            return f'<DataArray {attrs} format="ascii">{" ".join(map(str, values))}</DataArray>'
        raw = struct.pack(f"<{len(values)}{fmt}", *values)
        if encoding == "zlib":
            comp = zlib.compress(raw)
            blob = struct.pack("<4I", 1, len(raw), len(raw), len(comp)) + comp
        else:
            blob = struct.pack("<I", len(raw)) + raw
        return f'<DataArray {attrs} format="binary">{b64encode(blob).decode()}</DataArray>'

    compressor = ' compressor="vtkZLibDataCompressor"' if encoding == "zlib" else ""
    return (f'<?xml version="1.0"?>\n<VTKFile type="PolyData" version="1.0" '
            f'byte_order="LittleEndian" header_type="UInt32"{compressor}><PolyData>'
            f'<Piece NumberOfPoints="{len(P)}" NumberOfPolys="{len(T)}">'
            f'<Points>{array("Float32", "Points", pts, "f", 3)}</Points>'
            f'<Polys>{array("Int32", "connectivity", conn, "i")}{array("Int32", "offsets", offs, "i")}</Polys>'
            f'<CellData>{array("Int32", "ModelFaceID", [1] * len(T), "i")}</CellData>'
            '</Piece></PolyData></VTKFile>\n').encode()


def main():
    readers, options = Path(sys.argv[1]), Path(sys.argv[2])
    readers.mkdir(parents=True, exist_ok=True)
    options.mkdir(parents=True, exist_ok=True)
    seeds = {
        "ascii.stl": stl_ascii(),
        "ascii-crlf.stl": stl_ascii(eol="\r\n"),
        "ascii-cr.stl": stl_ascii(eol="\r"),
        "ascii-bom.stl": b"\xef\xbb\xbf" + stl_ascii(),
        "ascii-utf16.stl": b"\xff\xfe" + stl_ascii().decode().encode("utf-16-le"),
        "binary.stl": stl_binary(),
        "binary.stl.gz": gzip.compress(stl_binary()),
        "octa.obj": obj(),
        "ascii.ply": ply(False),
        "binary.ply": ply(True),
        "octa.vtk": vtk_legacy(),
        "ascii.vtp": vtp("ascii"),
        "binary.vtp": vtp("binary"),
        "zlib.vtp": vtp("zlib"),
    }
    for name, data in seeds.items():
        (readers / name).write_bytes(data)
    texts = ["0.2", "1e-30", "-1", "nan", "inf", "3", "auto", "off", "1,2,3,0,0,1", "2=aorta",
             "1=3", "mm", "m", "4.1", "2.2", "0x10", "1e309", " 5", "5 ", "", "K=L", "10"]
    for i in range(96):
        (options / f"opt{i}").write_bytes(bytes([i]) + texts[i % len(texts)].encode())


if __name__ == "__main__":
    main()
