#!/usr/bin/env python3
"""Output checksums: every real surface meshed as a new user meshes it (default
options), plus a few option sets on one file and the other output formats,
each output hashed (SHA-256 of its bytes; a refusal hashes its message).

A refactor must not change a byte: write the checksums before it
(--write FILE), check them after (--check FILE). The MSH header holds the
program's version and the input's hash only, no date or commit, so equal
inputs and equal code give equal bytes; the meshes are also the same on any
thread count (tests/pipeline, the determinism tests).

Usage:
  validation/checksums.py --vesselmesh build/vesselmesh --write before.json
  validation/checksums.py --vesselmesh build/vesselmesh --check before.json
"""
import argparse
import hashlib
import json
import pathlib
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parent.parent

# Extra runs on one file: (name, file, options, output name).
EXTRA = [
    ("bifurcation wall+layers", "vascular/bifurcation.stl", ["--wall-thickness", "0.1", "--layers", "3"], "out.msh"),
    ("bifurcation vtu", "vascular/bifurcation.stl", ["--format", "vtu"], "out.vtu"),
    ("bifurcation msh 2.2", "vascular/bifurcation.stl", ["--msh-version", "2.2"], "out.msh"),
    ("bifurcation foam", "vascular/bifurcation.stl", ["--format", "foam"], "out"),
    ("bifurcation mesh-complete", "vascular/bifurcation.stl", ["--format", "mesh-complete"], "out"),
    ("carotid per-circumference 12 no layers", "vascular/carotid-metres.stl",
     ["--per-circumference", "12", "--layers", "0"], "out.msh"),
    ("arch family 2", "vascular/aortic-arch.stl", ["--family", "2", "--per-circumference", "12"], "out.msh"),
]


def digest(path: pathlib.Path) -> str:
    h = hashlib.sha256()
    files = sorted(p for p in path.rglob("*") if p.is_file()) if path.is_dir() else [path]
    for f in files:
        if path.is_dir():
            h.update(str(f.relative_to(path)).encode() + b"\0")
        h.update(f.read_bytes())
    return h.hexdigest()


def run(vesselmesh: str, src: pathlib.Path, options: list[str], out_name: str) -> str:
    with tempfile.TemporaryDirectory() as tmp:
        out = pathlib.Path(tmp) / out_name
        r = subprocess.run([vesselmesh, "mesh", str(src), "-o", str(out), "--quiet", *options],
                           capture_output=True, text=True)
        if r.returncode != 0:
            return "refused:" + hashlib.sha256(r.stderr.encode()).hexdigest()
        # The family table holds each member's time: not hashed.
        outs = [p for p in pathlib.Path(tmp).iterdir() if "_family." not in p.name]
        h = hashlib.sha256()
        for p in sorted(outs):
            h.update(p.name.encode() + b"\0" + digest(p).encode())
        return h.hexdigest()


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--vesselmesh", default=str(ROOT / "build/vesselmesh"))
    ap.add_argument("--data", default=str(ROOT / "../shared/data"))
    group = ap.add_mutually_exclusive_group(required=True)
    group.add_argument("--write", metavar="FILE")
    group.add_argument("--check", metavar="FILE")
    args = ap.parse_args()
    data = pathlib.Path(args.data)
    runs = [(f"{p.parent.name}/{p.name} defaults", p, [], "out.msh")
            for d in ("vascular", "vascular-hard") for p in sorted((data / d).glob("*"))
            if p.suffix in (".stl", ".vtp", ".vtk", ".vtu", ".obj", ".ply")]
    runs += [(name, data / f, o, out) for name, f, o, out in EXTRA if (data / f).exists()]
    sums = {}
    for name, src, options, out_name in runs:
        sums[name] = run(args.vesselmesh, src, options, out_name)
        print(f"{sums[name][:16]}  {name}", flush=True)
    if args.write:
        pathlib.Path(args.write).write_text(json.dumps(sums, indent=1) + "\n")
        return 0
    want = json.loads(pathlib.Path(args.check).read_text())
    differ = [k for k in want if sums.get(k) != want[k]]
    for k in differ:
        print(f"DIFFERS: {k}")
    print(f"{len(want) - len(differ)} of {len(want)} outputs byte-identical")
    return 1 if differ else 0


if __name__ == "__main__":
    sys.exit(main())
