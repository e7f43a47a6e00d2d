#!/usr/bin/env python3
"""Every real file meshed as a new user meshes it: `vesselmesh mesh FILE -o
OUT.msh` with default options, natively and in WebAssembly under Node
(validation/wasm_mesh.mjs), the median of several runs each, with the peak
memory and, from the native run's report, where the time goes (the
preparation and checks, the surface's stages, its fidelity rounds, the
volume). Reads ../shared/data/vascular and ../shared/data/vascular-hard in
place (never copied).

With --against OLD (another build's vesselmesh, e.g. a release built from
its commit beside this one), each file is meshed by both in turn, natively
(runs alternating, so that both see the same machine), and the table gives
the ratio old / new of the medians, each one's fidelity share and its wall
quality (gamma_k min / mean).

usage: default_runs.py [--runs N] [--threads T] [--files a.stl,b.vtp] [--no-wasm]
                       [--vesselmesh PATH] [--against OLD] [--json OUT.json]
"""
import argparse
import json
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import benchutil  # noqa: E402

HARD = os.path.normpath(os.path.join(benchutil.ROOT, "..", "shared", "data", "vascular-hard"))
WASM_MESH = os.path.join(benchutil.ROOT, "validation", "wasm_mesh.mjs")


def surfaces(folder):
    if not os.path.isdir(folder):
        return []
    return sorted(os.path.join(folder, f) for f in os.listdir(folder)
                  if f.endswith((".stl", ".vtp", ".vtk", ".obj", ".ply")))


def mesh_once(vesselmesh, path, threads, tmp):
    """One native default run: (seconds, its report) or (None, stderr)."""
    out, rep = os.path.join(tmp, "out.msh"), os.path.join(tmp, "report.json")
    r = benchutil.run_measured([vesselmesh, "mesh", path, "-o", out, "--report", rep, "--quiet",
                                "--threads", str(threads)])
    if r["rc"] != 0:
        return None, r["stderr"].strip()[-300:]
    return r["seconds"], json.load(open(rep))


def compare(args, files):
    """Each file meshed by --against (old) and --vesselmesh (new) in turn."""
    print(f"load average {benchutil.loadavg()[0]:.2f}; {args.runs} runs each, alternating, "
          f"{args.threads} threads; old {args.against}, new {args.vesselmesh}")
    print("| file | old s | new s | old / new | fidelity share old / new | "
          "wall gamma_k min old / new | mean old / new | far input vertices old / new |")
    print("|---|---|---|---|---|---|---|---|")
    rows, ok = [], True
    with tempfile.TemporaryDirectory() as tmp:
        for path in files:
            seconds = {"old": [], "new": []}
            reports = {}
            for _ in range(args.runs):
                for key, exe in (("old", args.against), ("new", args.vesselmesh)):
                    s, rep = mesh_once(exe, path, args.threads, tmp)
                    if s is None:
                        print(f"{os.path.basename(path)}: {key} failed: {rep}")
                        ok = False
                        continue
                    seconds[key].append(s)
                    reports[key] = rep
            if not seconds["old"] or not seconds["new"]:
                continue
            row = dict(file=os.path.basename(path))
            for key in ("old", "new"):
                o = reports[key]["output"]
                fidelity = o["remesh"]["seconds"]["fidelity"]
                row[key] = dict(seconds=benchutil.median(seconds[key]),
                                fidelity_share=fidelity / reports[key]["seconds"],
                                gamma_min=o["quality"]["min"], gamma_mean=o["quality"]["mean"],
                                far=o["remesh"]["fidelity"]["input_gap_vertices"])
            old, new = row["old"], row["new"]
            row["ratio"] = old["seconds"] / new["seconds"]
            rows.append(row)
            print(f"| {row['file']} | {old['seconds']:.2f} | {new['seconds']:.2f} | "
                  f"{row['ratio']:.2f} | {100 * old['fidelity_share']:.0f} % / "
                  f"{100 * new['fidelity_share']:.0f} % | {old['gamma_min']:.3f} / "
                  f"{new['gamma_min']:.3f} | {old['gamma_mean']:.4f} / {new['gamma_mean']:.4f} | "
                  f"{old['far']} / {new['far']} |", flush=True)
    if rows:
        total_old = sum(r["old"]["seconds"] for r in rows)
        total_new = sum(r["new"]["seconds"] for r in rows)
        print(f"all files: old {total_old:.2f} s, new {total_new:.2f} s, "
              f"old / new {total_old / total_new:.2f}; smallest ratio "
              f"{min(r['ratio'] for r in rows):.2f}")
    if args.json:
        os.makedirs(os.path.dirname(os.path.abspath(args.json)), exist_ok=True)
        json.dump(dict(runs=args.runs, threads=args.threads, against=args.against, rows=rows),
                  open(args.json, "w"), indent=1)
    return 0 if ok else 1


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--files", help="comma-separated file names (default: all)")
    ap.add_argument("--no-wasm", action="store_true")
    ap.add_argument("--vesselmesh", default=benchutil.VESSELMESH)
    ap.add_argument("--against", help="another vesselmesh to compare with, run alternately")
    ap.add_argument("--json")
    args = ap.parse_args()
    files = surfaces(benchutil.DATA) + surfaces(HARD)
    if args.files:
        files = [f for f in files if os.path.basename(f) in args.files.split(",")]
    if args.against:
        return compare(args, files)
    print(f"load average {benchutil.loadavg()[0]:.2f}; {args.runs} runs each, {args.threads} threads")
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        out, rep = os.path.join(tmp, "out.msh"), os.path.join(tmp, "report.json")
        for path in files:
            name = os.path.basename(path)
            native, wasm = [], []
            report = None
            for _ in range(args.runs):
                r = benchutil.run_measured([args.vesselmesh, "mesh", path, "-o", out, "--report", rep,
                                            "--quiet", "--threads", str(args.threads)])
                if r["rc"] != 0:
                    print(f"{name}: failed: {r['stderr'].strip()[-300:]}")
                    break
                native.append(r)
                report = json.load(open(rep))
                if not args.no_wasm:
                    w = benchutil.run_measured(["node", WASM_MESH, path, out,
                                                json.dumps({"threads": 1})])
                    if w["rc"] == 0:
                        wasm.append(w)
            if not native:
                rows.append(dict(file=name, ok=False))
                continue
            o = report["output"]
            remesh = o.get("remesh", {}).get("seconds", {})
            surface = sum(v for k, v in remesh.items() if k != "fidelity")
            volume = sum(o.get("volume", {}).get("seconds", {}).values())
            row = dict(
                file=name, ok=True,
                native_s=benchutil.median([r["seconds"] for r in native]),
                native_mb=max(r["peak_rss_mb"] for r in native),
                wasm_s=benchutil.median([r["seconds"] for r in wasm]) if wasm else None,
                wasm_mb=max(r["peak_rss_mb"] for r in wasm) if wasm else None,
                job_s=report["seconds"], surface_s=surface, fidelity_s=remesh.get("fidelity", 0.0),
                volume_s=volume, tetrahedra=o.get("volume", {}).get("tetrahedra", 0),
                openings=len(report["input"]["openings"]), unit=report["input"]["units"]["unit"],
                warnings=len(report.get("warnings", [])))
            row["rest_s"] = max(0.0, row["job_s"] - surface - row["fidelity_s"] - volume)
            rows.append(row)
    print()
    print("| file | native s | MB | wasm (Node, 1 thread) s | MB | of the native job: surface / fidelity / "
          "volume / preparation and the rest, s | tetrahedra | openings | unit |")
    print("|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        if not r["ok"]:
            print(f"| {r['file']} | failed | | | | | | | |")
            continue
        wasm = f"{r['wasm_s']:.2f} | {r['wasm_mb']:.0f}" if r["wasm_s"] is not None else "- | -"
        print(f"| {r['file']} | {r['native_s']:.2f} | {r['native_mb']:.0f} | {wasm} | "
              f"{r['surface_s']:.2f} / {r['fidelity_s']:.2f} / {r['volume_s']:.2f} / {r['rest_s']:.2f} | "
              f"{r['tetrahedra']} | {r['openings']} | {r['unit']} |")
    if args.json:
        os.makedirs(os.path.dirname(os.path.abspath(args.json)), exist_ok=True)
        json.dump(dict(runs=args.runs, threads=args.threads, rows=rows), open(args.json, "w"), indent=1)
    return 0 if all(r["ok"] for r in rows) else 1


if __name__ == "__main__":
    sys.exit(main())
