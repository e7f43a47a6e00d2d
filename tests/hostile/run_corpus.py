#!/usr/bin/env python3
"""The hostile-input corpus: several hundred generated cases of broken,
odd or huge inputs and extreme option values, each run through the
`vesselmesh` CLI under a memory cap (4 GiB address space, what a browser
tab has) and a time limit. Every case must end in one of the promised
ways:

- exit 2 (bad usage) or exit 1 with a `vesselmesh: error:` message: no
  signal, no sanitizer or C++ runtime report, no "out of memory" blamed on
  a small input;
- exit 0 with a valid mesh: the MSH file reads back, no tetrahedron has a
  non-positive volume, every element is in a physical group, and the wall
  encloses within 5% of the input's volume (the report's volume_change),
  unless the case itself allows more;
- for the cases in REFUSED, exit 1 with their message under their own,
  smaller memory cap (a 1 GiB gzip of zeros refused without inflating it).

Nothing is stored: the inputs are made from a small generated tube and
bifurcation (`vesselmesh phantom`) by byte-level mutations and small
hand-written files. Usage:

  run_corpus.py PATH/TO/vesselmesh [--jobs N] [--only SUBSTRING] [--list]
"""
import argparse
import gzip
import json
import math
import os
import random
import resource
import struct
import subprocess
import sys
import tempfile
import time
import zlib
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "validation"))
import numpy as np  # noqa: E402
from meshquality import read_msh, signed_tet_volumes  # noqa: E402

MEMORY_CAP = 4 << 30
TIMEOUT_S = 120
BAD_TEXT = ("Sanitizer", "terminate called", "Aborted", "Segmentation", "std::", "what():")


# Cases that must be refused with exit 1 and a message containing the given
# words, under a smaller memory cap (bytes of address space) than MEMORY_CAP.
REFUSED = {
    # 1 GiB of zeros is refused from its first 64 KiB, never inflated whole.
    "input/gzip-zeros-1G": ("its first 65536 decompressed bytes are not the start of a surface file", 256 << 20),
}


def limit_memory(cap=MEMORY_CAP):
    resource.setrlimit(resource.RLIMIT_AS, (cap, cap))


# ---------------------------------------------------------------- inputs


def stl_triangles(data):
    """The (n, 9) float32 corners of a binary STL."""
    n = struct.unpack_from("<I", data, 80)[0]
    rec = np.frombuffer(data, dtype=np.uint8, count=50 * n, offset=84).reshape(n, 50)
    return rec[:, 12:48].copy().view("<f4").reshape(n, 9)


def stl_binary(tri):
    tri = np.asarray(tri, dtype="<f4").reshape(-1, 9)
    rec = np.zeros((len(tri), 50), dtype=np.uint8)
    rec[:, 12:48] = tri.view(np.uint8).reshape(len(tri), 36)
    return b"corpus".ljust(80, b" ") + struct.pack("<I", len(tri)) + rec.tobytes()


def stl_ascii(tri, name="corpus", eol="\n", fmt="{:.9g}"):
    out = [f"solid {name}"]
    for t in np.asarray(tri).reshape(-1, 9):
        out += ["facet normal 0 0 0", "outer loop"]
        out += ["vertex " + " ".join(fmt.format(float(x)) for x in t[3 * k:3 * k + 3]) for k in range(3)]
        out += ["endloop", "endfacet"]
    return (eol.join(out + [f"endsolid {name}", ""])).encode()


def gzip_zeros(n):
    """A gzip member of n zero bytes (a multiple of 1 MiB), made 1 MiB at a time
    at level 1 (1 GiB in 4.5 MB, as gzip -1 makes it)."""
    z, chunk = zlib.compressobj(1, zlib.DEFLATED, 16 + 15), bytes(1 << 20)
    return b"".join(z.compress(chunk) for _ in range(n >> 20)) + z.flush()


def input_cases(base, bif, tmp):
    """(name, bytes or path, extra args) of the input mutations."""
    rng = random.Random(1234)
    tri = stl_triangles(base)
    cases = []

    def add(name, data, args=()):
        cases.append((f"input/{name}", data, list(args)))

    for cut in (0, 1, 50, 83, 84, 100, 134, len(base) // 2, len(base) - 50, len(base) - 1):
        add(f"truncated-{cut}", base[:cut])
    for k in range(40):
        b = bytearray(base)
        for _ in range(1 + k % 4):
            b[rng.randrange(84, len(b))] ^= 1 << rng.randrange(8)
        add(f"bitflip-{k}", bytes(b))
    for k in range(10):  # exponent bits: huge or tiny coordinates
        b = bytearray(base)
        t = rng.randrange(len(tri))
        b[84 + 50 * t + 12 + 4 * rng.randrange(9) + 3] ^= 0x40
        add(f"exponent-{k}", bytes(b))
    for count in (0, 1, len(tri) - 1, len(tri) + 1, 2**31, 2**32 - 1):
        b = bytearray(base)
        struct.pack_into("<I", b, 80, count)
        add(f"header-count-{count}", bytes(b))
    for k, bad in enumerate((math.nan, math.inf, -math.inf, 3.5e38, 1e-45)):
        t = tri.copy()
        t[k * 7 % len(t), k % 9] = bad
        add(f"nonfinite-{k}", stl_binary(t))
    for far in (1e3, 1e6, 1e30):
        outlier = np.array([[far, 0, 0, far + 1, 0, 0, far, 1, 0]], dtype=np.float32)
        add(f"far-triangle-{far:g}", stl_binary(np.vstack([tri, outlier])))
        add(f"far-triangle-largest-{far:g}", stl_binary(np.vstack([tri, outlier])), ["--largest-component-only"])
    for scale in (1e-6, 1e-3, 1e3, 1e6):
        add(f"scaled-{scale:g}", stl_binary(tri * scale))
    for offset in (1e3, 1e5, 1e7):
        add(f"offset-{offset:g}", stl_binary(tri + np.float32(offset)))
        add(f"offset-ascii-{offset:g}", stl_ascii(tri.astype(np.float64) + offset, fmt="{:.17g}"))
    for k in range(8):  # holes: triangles removed
        keep = np.ones(len(tri), bool)
        keep[rng.sample(range(len(tri)), 1 + 3 * k)] = False
        add(f"holes-{k}", stl_binary(tri[keep]))
    for k in range(4):  # duplicated and reversed triangles
        t = tri.copy()
        idx = rng.sample(range(len(t)), 5 + 10 * k)
        extra = t[idx][:, [0, 1, 2, 6, 7, 8, 3, 4, 5]] if k % 2 else t[idx]
        add(f"duplicates-{k}", stl_binary(np.vstack([t, extra])))
    for k in range(4):  # flipped patches
        t = tri.copy()
        idx = rng.sample(range(len(t)), 1 + 20 * k)
        t[idx] = t[idx][:, [0, 1, 2, 6, 7, 8, 3, 4, 5]]
        add(f"flipped-{k}", stl_binary(t))
    add("two-copies", stl_binary(np.vstack([tri, tri + np.float32(10)])))
    add("two-copies-largest", stl_binary(np.vstack([tri, tri * np.float32(0.5) + np.float32(10)])), ["--largest-component-only"])
    add("overlapping-copies", stl_binary(np.vstack([tri, tri + np.float32(0.3)])))
    add("single-triangle", stl_binary(tri[:1]))
    add("two-triangles", stl_binary(tri[:2]))
    add("all-one-point", stl_binary(np.zeros((20, 9), np.float32)))
    disk = []
    for k in range(32):
        a, b = 2 * math.pi * k / 32, 2 * math.pi * (k + 1) / 32
        disk.append([0, 0, 0, math.cos(a), math.sin(a), 0, math.cos(b), math.sin(b), 0])
    add("flat-disk", stl_binary(np.array(disk)))
    add("flat-disk-doubled", stl_binary(np.vstack([np.array(disk), np.array(disk)[:, [0, 1, 2, 6, 7, 8, 3, 4, 5]]])))
    add("ascii", stl_ascii(tri))
    add("ascii-crlf", stl_ascii(tri, eol="\r\n"))
    add("ascii-cr", stl_ascii(tri, eol="\r"))
    add("ascii-bom", b"\xef\xbb\xbf" + stl_ascii(tri))
    add("ascii-utf16", b"\xff\xfe" + stl_ascii(tri).decode().encode("utf-16-le"))
    add("ascii-nul-name", stl_ascii(tri, name="a\x00b\x0cc"))
    add("ascii-long-numbers", stl_ascii(tri, fmt="{:.70f}"))
    add("ascii-no-endsolid", stl_ascii(tri).rsplit(b"endsolid", 1)[0])
    add("ascii-truncated", stl_ascii(tri)[: len(stl_ascii(tri)) // 3])
    add("ascii-quad", b"solid q\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid q\n")
    add("ascii-garbage-number", stl_ascii(tri).replace(b"vertex ", b"vertex 1.2.3 ", 1))
    add("text", b"hello, this is not a mesh at all, but it is long enough to pass the binary header\n" * 3)
    add("png", b"\x89PNG\r\n\x1a\n" + bytes(300))
    add("zip", b"PK\x03\x04" + bytes(300))
    add("gzip", gzip.compress(base))
    add("gzip-truncated", gzip.compress(base)[:500])
    add("gzip-twice", gzip.compress(gzip.compress(base)))
    add("gzip-of-nothing", gzip.compress(b""))
    add("gzip-zeros-64M", gzip.compress(bytes(64 << 20)))
    add("gzip-zeros-1G", gzip_zeros(1 << 30))
    add("obj-bad-index", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n")
    add("obj-negative-index", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -3\nf -1 -2 -9\n")
    add("obj-huge-index", b"v 0 0 0\nf 1 2 99999999999999999999\n")
    add("ply-count-lies", b"ply\nformat ascii 1.0\nelement vertex 4000000000\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n")
    add("ply-binary-short", b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n" + bytes(20))
    add("vtk-count-lies", b"# vtk DataFile Version 3.0\nx\nASCII\nDATASET POLYDATA\nPOINTS 999999999 float\n0 0 0\nPOLYGONS 1 4\n3 0 1 2\n")
    add("vtp-empty", b'<?xml version="1.0"?><VTKFile type="PolyData"><PolyData></PolyData></VTKFile>')
    add("vtp-count-lies", b'<VTKFile type="PolyData" version="1.0" byte_order="LittleEndian"><PolyData><Piece NumberOfPoints="3000000000" NumberOfPolys="1"><Points><DataArray type="Float32" NumberOfComponents="3" format="ascii">0 0 0</DataArray></Points></Piece></PolyData></VTKFile>')
    add("bifurcation", bif)
    add("empty", b"")
    cases.append(("input/directory", Path(tmp), []))
    cases.append(("input/dev-null", Path("/dev/null"), []))
    cases.append(("input/missing", Path(tmp) / "missing.stl", []))
    return cases


# ---------------------------------------------------------------- options


def option_values(spec):
    """Hostile texts for one numeric option of the table."""
    lo, hi = spec.get("min"), spec.get("max")
    vals = ["0", "-1", "1e-30", "1e-300", "1e300", "nan", "inf", "-inf", "abc", "", "1e999", "0x10"]
    if lo is not None:
        vals += [repr(lo), repr(lo - 1e-9 - abs(lo) * 1e-9), repr(lo + max(1e-3, abs(lo) * 1e-3))]
    if hi is not None and hi < 1e30:
        vals += [repr(hi), repr(hi * (1 + 1e-9) + 1e-9)]
    if spec["type"] == "integer":
        vals += ["1.5", "2147483648", "-2147483649", "1e10"]
    return vals


SKIP = {"output", "report", "report_html", "name", "quiet", "verify", "format", "msh_version", "output_units", "units", "solver"}
# Options that change what "the wall's volume" means, or allow more change.
VOLUME_CHANGING = {"flow_extension", "clip", "clip_at", "clip_plane", "max_volume_change", "remesh", "largest_component_only"}


def option_cases(table):
    cases = []
    for spec in table:
        if "mesh" not in spec["commands"] or "cli" not in spec["faces"] or spec["id"] in SKIP:
            continue
        flag = "--" + spec["cli"]
        if spec["type"] in ("number", "integer"):
            for v in option_values(spec):
                text = v if spec["perOpening"] != "required" else f"1={v}"
                cases.append((f"option/{spec['id']}={v}", "tube", [flag, text], spec["id"]))
        elif spec["type"] == "numbers":
            n = spec["listSize"]
            for v in ("nan", "1e300", "0", "abc", ",".join(["0"] * (n - 1)), ",".join(["1e-300"] * n)):
                cases.append((f"option/{spec['id']}={v}", "tube", [flag, v], spec["id"]))
        elif spec["type"] in ("choice", "text"):
            for v in list(spec.get("choices", [])) + ["bogus", "", "1e300"]:
                cases.append((f"option/{spec['id']}={v}", "tube", [flag, v], spec["id"]))
    # Combinations users reach for.
    combos = [
        ["--size", "5", "--layers", "0"],
        ["--size", "0.3", "--layers", "0"],
        ["--size", "1e300", "--surface-only"],
        ["--size", "1e-4"],
        ["--per-circumference", "1e6"],
        ["--core-size", "1e-4"],
        ["--curvature", "1e6"],
        ["--first-layer", "1e-12"],
        ["--wall-layers", "5"],
        ["--inlet", "1e10"],
        ["--layers", "100", "--growth", "3"],
        ["--layers", "100", "--layer-thickness", "0.99"],
        ["--wall-thickness", "0.99", "--wall-layers", "100"],
        ["--feature-angle", "1"],
        ["--fidelity", "1", "--size", "0.05"],
        ["--size-min", "10", "--size-max", "0.01"],
        ["--flow-extension", "100"],
        ["--flow-extension", "100", "--size", "0.5"],
        ["--max-elements", "1000"],
        ["--clip", "auto"],
        ["--clip-plane", "0,0,0,0,0,1"],
        ["--clip-plane", "0,0,1e9,0,0,1"],
        ["--clip-at", "0,0,0"],
        ["--clip-at", "1e30,0,0"],
        ["--smooth", "1000"],
        ["--no-remesh"],
        ["--prisms", "--layers", "10", "--first-layer", "0.001"],
        ["--solver", "openfoam"],
        ["--for", "openfoam", "--first-layer-yplus", "1", "--inlet-velocity", "100"],
    ]
    for k, c in enumerate(combos):
        cases.append((f"combo/{k}:{' '.join(c)}", "bifurcation" if k % 2 else "tube", c, None))
    return cases


# ---------------------------------------------------------------- checks


def check_mesh(path, report_path, allow_volume):
    """Why the written mesh breaks the promise, or None."""
    try:
        xyz, el = read_msh(path)
    except Exception as e:  # noqa: BLE001 - any failure to read is a finding
        return f"the MSH does not read back: {e}"
    if not np.all(np.isfinite(xyz)):
        return "non-finite node coordinates"
    tet = el.get(4)
    if tet is not None and len(tet):
        v = signed_tet_volumes(xyz, tet)
        if np.any(v <= 0):
            return f"{int(np.sum(v <= 0))} tetrahedra with a non-positive volume"
    text = Path(path).read_text()
    if "$PhysicalNames" not in text:
        return "no physical groups"
    report = json.loads(Path(report_path).read_text())
    change = report.get("output", {}).get("remesh", {}).get("fidelity", {}).get("volume_change")
    if change is not None and abs(change) > 0.05 and not allow_volume:
        return f"exit 0 with a volume change of {100 * change:.1f}%"
    return None


def run_case(vm, case, inputs, tmp):
    name, source, args, option = case
    work = Path(tempfile.mkdtemp(dir=tmp))
    if isinstance(source, Path):
        infile = source
    elif isinstance(source, (bytes, bytearray)):
        infile = work / "in.stl"
        infile.write_bytes(source)
    else:
        infile = inputs[source]
    out, rep = work / "out.msh", work / "report.json"
    cmd = [vm, "mesh", str(infile), "-o", str(out), "--report", str(rep), "--quiet"] + args
    refused, cap = REFUSED.get(name, (None, MEMORY_CAP))
    t0 = time.time()
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, errors="replace", timeout=TIMEOUT_S, preexec_fn=lambda: limit_memory(cap))
    except subprocess.TimeoutExpired:
        return name, f"hang: no end within {TIMEOUT_S} s", TIMEOUT_S
    dt = time.time() - t0
    err = p.stderr + p.stdout
    problem = None
    if p.returncode < 0:
        problem = f"killed by signal {-p.returncode}"
    elif p.returncode not in (0, 1, 2):
        problem = f"exit {p.returncode}"
    elif any(b in err for b in BAD_TEXT):
        problem = "a runtime report: " + err.strip().splitlines()[-1][:200]
    elif refused and (p.returncode != 1 or refused not in err):
        problem = f"exit {p.returncode} under a {cap >> 20} MiB cap, not refused with '{refused}': " + err.strip()[:200]
    elif p.returncode == 1 and "vesselmesh: error:" not in err:
        problem = "exit 1 without an error message"
    elif p.returncode == 1 and "out of memory" in err and infile.exists() and infile.is_file() and infile.stat().st_size < (64 << 20):
        problem = "out of memory on a small input: " + err.strip()[:200]
    elif p.returncode == 0:
        allow = option in VOLUME_CHANGING or any(a.lstrip("-").replace("-", "_") in VOLUME_CHANGING for a in args if a.startswith("--"))
        # A family (--family N) writes out_0.msh .. out_N-1.msh instead.
        members = [out] if out.exists() else sorted(work.glob("out_*.msh"))
        problem = next(filter(None, (check_mesh(m, rep, allow) for m in members or [out])), None)
    return name, problem, dt


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("vesselmesh")
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 2)
    ap.add_argument("--only", default="")
    ap.add_argument("--list", action="store_true")
    a = ap.parse_args()
    vm = str(Path(a.vesselmesh).resolve())
    with tempfile.TemporaryDirectory() as tmp:
        inputs = {"tube": Path(tmp) / "tube.stl", "bifurcation": Path(tmp) / "bif.stl"}
        subprocess.run([vm, "phantom", str(inputs["tube"]), "--kind", "tube", "--voxel", "0.3"], check=True, capture_output=True)
        subprocess.run([vm, "phantom", str(inputs["bifurcation"]), "--kind", "bifurcation", "--voxel", "0.25"], check=True, capture_output=True)
        table = json.loads(subprocess.run([vm, "options", "--json"], check=True, capture_output=True, text=True).stdout)
        cases = [(n, d, args, None) for n, d, args in input_cases(inputs["tube"].read_bytes(), inputs["bifurcation"].read_bytes(), tmp)]
        cases += option_cases(table)
        cases = [c for c in cases if a.only in c[0]]
        if a.list:
            print("\n".join(c[0] for c in cases))
            return 0
        t0 = time.time()
        with ThreadPoolExecutor(a.jobs) as pool:
            results = list(pool.map(lambda c: run_case(vm, c, inputs, tmp), cases))
    failed = [(n, p) for n, p, _ in results if p]
    slow = sorted(results, key=lambda r: -r[2])[:5]
    for n, p in failed:
        print(f"FAIL {n}: {p}")
    print("slowest: " + ", ".join(f"{n} {t:.1f} s" for n, _, t in slow))
    print(f"hostile corpus: {len(results)} cases, {len(failed)} failed, {time.time() - t0:.0f} s "
          f"(memory cap {MEMORY_CAP >> 30} GiB, {TIMEOUT_S} s a case)")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
