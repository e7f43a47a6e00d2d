#!/usr/bin/env python3
"""Speed benchmark of issue 3 (and, with --volume, of the volume issue;
with --threads, the side-by-side run of issue 22): one input at one uniform
size, medians of repeated runs, one at a time, alternating run by run.

  native  `vesselmesh mesh IN --surface-only -o OUT --size H [--threads T]`
          (>= 5 runs): wall time of the process, its CPU time and peak RSS
          (GNU time %U+%S, %M); without --threads the CLI's default (all cores)
  wasm    bench/wasm_mesh_bench.mjs: api.mesh(bytes, {size: H}) under Node
          in one process (>= 5 runs; module loaded once via wasmBinary),
          process peak RSS (includes Node itself; its baseline is shown);
          with --chromium (or --chromium-runs N) also in Chromium
          (bench/wasm_chromium_bench.mjs; wall time only, peak = JS heap),
          on a cross-origin isolated page: with --threads, once per T (the
          threaded core on T threads; T = 1 the single-threaded core).
          Node likewise, once per T (the threaded core's pool on
          worker_threads); without --threads the single-threaded core.
          Both run with --serve, one run per line sent, so that their runs
          alternate with the others.
  Gmsh    bench/gmsh_reference.py (>= 3 runs), one thread (--threads: each
          T): per-stage medians; its time is the sum of its stages (merge,
          classify, createGeometry, surface[, caps + volume]) without
          Python/Gmsh start-up, i.e. the comparison is generous to Gmsh.

Every round runs each variant once (native per T, Gmsh per T, Node,
Chromium) while it has runs left, so that a drift of the (shared) machine's
speed weighs on all alike. The table has one row per variant and its
speed-up against Gmsh with one thread and with the same threads.
With --volume and --threads, the stages follow per T (stage_split): our
surface and volume stages against Gmsh's, and what the whole run may take
for the issue's targets.

Wall-clock medians decide the targets; CPU-time medians (user + system of
the process over all its threads, Gmsh: of its stages) are printed beside
them because the machine is shared and wall time then includes waiting for
a core.

Targets (issue 3): aortic-arch.stl at h = 0.06 natively >= 3x faster than
Gmsh's surface pipeline; wasm within 1.6x of native. With --volume: the full
pipeline natively >= 3x faster than Gmsh with HXT: with --volume, `mesh`
runs without --surface-only (caps and tetrahedra), and the table says when
its output has no tetrahedra (the comparison is then not valid). The median
tetrahedron edge of both outputs is printed: Gmsh's HXT fills the volume
coarser than h (about 1.4 h on the aortic arch at h = 0.06, where
vesselmesh's is 1.0 h), so a like-for-like run passes --core-size 1.4h.
Targets with --threads (issue 22, full pipeline, --core-size 0.084): native
on 1 thread >= 4.5x faster than Gmsh on 1 thread, on 2 threads >= 6.5x than
Gmsh on 2 threads; Chromium within 1.4x of native at the same thread count.

usage: remesh_speed.py [--file aortic-arch.stl] [--size 0.06] [--runs 5]
                       [--wasm-runs 5] [--gmsh-runs 3] [--volume [--layers N] [--core-size H]]
                       [--threads 1,2] [--no-wasm] [--chromium | --chromium-runs N]
                       [--no-gmsh] [--json OUT.json]
e.g. the side-by-side run of issue 22:
  remesh_speed.py --volume --size 0.06 --core-size 0.084 --layers 0 --threads 1,2 \
                  --chromium-runs 3 --json out/speed/side_by_side.json
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
# The quality measures live with the validation (validation/meshquality.py).
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "validation"))
import benchutil  # noqa: E402
import meshquality  # noqa: E402

TARGET_GMSH_RATIO = 3.0
TARGET_WASM_RATIO = 1.6
# Issue 22 (--threads): Gmsh with one thread / native with T threads, by T
# (the "against Gmsh 4.8 with one thread"); Chromium / native at the
# same thread count.
TARGET_GMSH_RATIO_BY_THREADS = {1: 4.5, 2: 6.5}
TARGET_CHROMIUM_RATIO = 1.4


class NativeBench:
    """`vesselmesh mesh` runs with `--threads T` (None: the CLI's default, all
    cores), one at a time (run() is interleaved with the other variants' so
    that all see the same machine); summary() aggregates them."""

    def __init__(self, a, path, tmp, threads=None):
        self.a, self.threads = a, threads
        self.name = "native" if threads is None else f"native {threads}T"
        tag = "" if threads is None else str(threads)
        self.out = os.path.join(tmp, f"native{tag}.msh")
        self.rep = os.path.join(tmp, f"native{tag}.json")
        self.cmd = [a.vesselmesh, "mesh", path, "-o", self.out, "--report", self.rep, "--quiet",
                    "--size", repr(a.size)] + volume_flags(a) + \
            ([] if threads is None else ["--threads", str(threads)])
        self.runs, self.error, self.report = [], None, None

    def run(self):
        if self.error:
            return
        r = benchutil.run_measured(self.cmd)
        if r["rc"] != 0:
            self.error = r["stderr"].strip()
            return
        self.report = json.load(open(self.rep))
        self.runs.append(dict(seconds=r["seconds"], cpu_seconds=r["cpu_seconds"], peak_rss_mb=r["peak_rss_mb"],
                              core_seconds=self.report["seconds"],
                              stages=self.report["output"].get("remesh", {}).get("seconds"),
                              volume_stages=self.report["output"].get("volume", {}).get("seconds")))
        print(f"  {self.name} run {len(self.runs)}: {r['seconds']:.3f} s (CPU {r['cpu_seconds']:.2f} s), "
              f"{r['peak_rss_mb']:.0f} MB", flush=True)

    def summary(self):
        a, runs = self.a, self.runs
        if self.error or not runs:
            return dict(ok=False, error=self.error or "no run", cmd=" ".join(self.cmd), threads=self.threads)
        o = self.report["output"]
        tets = sum(g["elements"] for g in o.get("groups", []) if g["dim"] == 3)
        # How finely the volume follows h: the median edge of the last run's
        # tetrahedra (Gmsh's is measured the same way in gmsh_reference.py).
        tet_edge = meshquality.msh_quality(self.out).get("median_tet_edge") if a.volume and tets else None
        stages = {k: benchutil.median([x["stages"][k] for x in runs]) for k in (runs[0]["stages"] or {})}
        volume_stages = {k: benchutil.median([x["volume_stages"][k] for x in runs])
                         for k in (runs[0]["volume_stages"] or {})}
        return dict(ok=True, cmd=" ".join(self.cmd), threads=self.threads, runs=runs,
                    median_seconds=benchutil.median([x["seconds"] for x in runs]),
                    median_core_seconds=benchutil.median([x["core_seconds"] for x in runs]),
                    median_cpu_seconds=benchutil.median([x["cpu_seconds"] for x in runs]),
                    stage_medians=stages, volume_stage_medians=volume_stages,
                    peak_rss_mb=max(x["peak_rss_mb"] for x in runs), triangles=o["triangles"],
                    quality=dict(min=o["quality"]["min"], mean=o["quality"]["mean"]), tets=tets,
                    median_tet_edge=tet_edge,
                    rss_source="GNU time" if os.access(benchutil.GNU_TIME, os.X_OK) else "wait4")


def stage_split(native, gmsh):
    """Seconds of the surface and volume stages, ours and Gmsh's (medians):
    ours, the report's remesh stages and its volume stages (layers, caps,
    boundary recovery, refinement and optimization); Gmsh's, classify,
    createGeometry and the surface mesh, then the caps' entities and the
    volume mesh (HXT); and the rest of our run (reading, preparation,
    assembly, checks, writing, process start). None without a volume."""
    ours_v = native.get("volume_stage_medians") or {}
    if not native.get("ok") or not gmsh or not gmsh.get("ok") or not ours_v:
        return None
    gs = gmsh["stage_medians"]
    surface = (sum(native["stage_medians"].values()),
               sum(gs.get(k, 0) for k in ("classify", "create_geometry", "surface_mesh")))
    volume = (sum(ours_v.get(k, 0) for k in ("layers", "caps", "recovery", "refinement")),
              sum(gs.get(k, 0) for k in ("caps_volume_entities", "volume_mesh")))
    return dict(surface=surface, volume=volume,
                rest=native["median_seconds"] - surface[0] - volume[0])


def volume_flags(a):
    """The job's flags beyond the size, the same for every runner: the surface
    alone, or the volume (like Gmsh's: no boundary layer unless --layers)."""
    if not a.volume:
        return ["--surface-only"]
    flags = ["--layers", str(a.layers)]
    if a.core_size:
        flags += ["--core-size", repr(a.core_size)]
    return flags


class WasmBench:
    """The wasm build under Node (bench/wasm_mesh_bench.mjs) or in Chromium
    (wasm_chromium_bench.mjs): the threaded core on `threads` threads, the
    single-threaded one on 1 (Node without --threads: the single-threaded
    core, no --threads passed); one process for all runs (the module loaded
    once), started with --serve, which runs once per line it reads, so that
    its runs alternate with the other variants'."""

    def __init__(self, a, path, chromium=False, threads=1):
        self.threads = threads
        self.name = f"{'chromium' if chromium else 'node'} {threads}T"
        self.proc, self.err, self.seconds, self.error = None, None, [], None
        node = shutil.which("node")
        script = "wasm_chromium_bench.mjs" if chromium else "wasm_mesh_bench.mjs"
        self.cmd = [node or "node", os.path.join(benchutil.BENCH, script), path, "--size", repr(a.size),
                    "--serve"] + volume_flags(a) + (["--threads", str(threads)] if chromium or a.threads else [])
        wasm = "vesselmesh_core.wasm" if threads == 1 else "vesselmesh_core_mt.wasm"
        if not node:
            self.error = "node not found"
        elif not os.path.exists(os.path.join(benchutil.ROOT, "wasm", "dist", wasm)):
            self.error = f"wasm/dist/{wasm} missing (build the wasm target)"

    def _fail(self, res=None):
        self.err.seek(0)
        self.error = (res or {}).get("error") or \
            (self.err.read().decode(errors="replace").strip() or f"exit {self.proc.poll()}")[-500:]

    def run(self):
        if self.error:
            return
        if self.proc is None:
            self.err = tempfile.TemporaryFile()
            self.proc = subprocess.Popen(self.cmd, stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=self.err)
        try:
            self.proc.stdin.write(b"run\n")
            self.proc.stdin.flush()
        except BrokenPipeError:
            return self._fail()
        for line in iter(self.proc.stdout.readline, b""):
            try:
                r = json.loads(line)
            except ValueError:
                continue  # not ours (the module's own output)
            if "run" in r:
                self.seconds.append(r["seconds"])
                cpu = f" (CPU {r['cpu_seconds']:.2f} s)" if "cpu_seconds" in r else ""
                print(f"  wasm ({self.name}) run {r['run']}: {r['seconds']:.3f} s{cpu}", flush=True)
                return
            if r.get("ok") is False:
                return self._fail(r)
        self._fail()

    def summary(self):
        """The script's own summary (printed when its stdin closes)."""
        if self.proc is None:
            return dict(ok=False, error=self.error or "no run")
        self.proc.stdin.close()
        lines = self.proc.stdout.read().decode(errors="replace").strip().splitlines()
        self.proc.wait()
        try:
            res = json.loads(lines[-1])
        except (ValueError, IndexError):
            res = None
        if self.error or not res or not res.get("ok"):
            if not self.error:
                self._fail(res)
            return dict(ok=False, error=self.error)
        res["process_peak_rss_mb"] = res.get("peak_rss_mb")
        return res


class GmshBench:
    """gmsh_reference.py runs with `--threads T`, one at a time, like NativeBench."""

    def __init__(self, a, path, tmp, threads=1):
        self.a, self.threads, self.name = a, threads, f"gmsh {threads}T"
        self.out = os.path.join(tmp, f"gmsh{threads}.json")
        self.cmd = [a.gmsh_python, os.path.join(benchutil.BENCH, "gmsh_reference.py"), path, "--size",
                    repr(a.size), "--threads", str(threads), "--json", self.out] + (["--volume"] if a.volume else [])
        self.runs = []
        self.error = None if benchutil.have_gmsh(a.gmsh_python) else "gmsh Python module not importable"

    def run(self):
        if self.error:
            return
        if os.path.exists(self.out):
            os.remove(self.out)
        r = benchutil.run_measured(self.cmd)
        if not os.path.exists(self.out):
            self.error = r["stderr"].strip()[-500:]
            return
        g = json.load(open(self.out))
        if not g.get("ok"):
            self.error = g.get("error")
            return
        g["process_seconds"] = r["seconds"]
        g["process_peak_rss_mb"] = r["peak_rss_mb"]
        self.runs.append(g)
        print(f"  {self.name} run {len(self.runs)}: " + ", ".join(f"{k} {v:.2f}" for k, v in g["seconds"].items()) +
              f" s (CPU {g['cpu_seconds']['total']:.2f} s; process {r['seconds']:.2f} s), "
              f"{r['peak_rss_mb']:.0f} MB", flush=True)

    def summary(self):
        runs = self.runs
        if self.error or not runs:
            return dict(ok=False, error=self.error or "no run", threads=self.threads)
        keys = list(runs[0]["seconds"])
        med = {k: benchutil.median([g["seconds"][k] for g in runs]) for k in keys}
        last = runs[-1]
        res = dict(ok=True, cmd=" ".join(self.cmd), threads=self.threads, stage_medians=med,
                   median_seconds=med["total"],
                   median_process_seconds=benchutil.median([g["process_seconds"] for g in runs]),
                   median_cpu_seconds=benchutil.median([g["cpu_seconds"]["total"] for g in runs]),
                   peak_rss_mb=max(g["process_peak_rss_mb"] for g in runs), triangles=last["triangles"],
                   quality=dict(min=last["gamma_k"]["min"], mean=last["gamma_k"]["mean"]),
                   runs=[dict(seconds=g["seconds"], cpu_seconds=g["cpu_seconds"],
                              process_seconds=g["process_seconds"],
                              peak_rss_mb=g["process_peak_rss_mb"], triangles=g["triangles"],
                              gamma_k=dict(min=g["gamma_k"]["min"], mean=g["gamma_k"]["mean"]),
                              tets=g.get("tets"), median_tet_edge=g.get("median_tet_edge"),
                              gamma_t=dict(min=g["gamma_t"]["min"], mean=g["gamma_t"]["mean"])
                              if g.get("gamma_t") else None)
                         for g in runs])
        if self.a.volume:
            res.update(tets=last.get("tets"), gamma_t=dict(min=last["gamma_t"]["min"], mean=last["gamma_t"]["mean"]))
        return res


def parse_threads(text):
    """--threads "1,2" -> [1, 2]; 0 stands for all cores."""
    if not text:
        return None
    return [int(t) or os.cpu_count() for t in text.split(",")]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--data", default=benchutil.DATA)
    ap.add_argument("--file", default="aortic-arch.stl")
    ap.add_argument("--size", type=float, default=0.06)
    ap.add_argument("--vesselmesh", default=benchutil.VESSELMESH)
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--wasm-runs", type=int, default=5)
    ap.add_argument("--gmsh-runs", type=int, default=3)
    ap.add_argument("--volume", action="store_true", help="full pipeline (STL -> MSH with tetrahedra)")
    ap.add_argument("--layers", type=int, default=0,
                    help="viscous layers in --volume mode (default 0: like Gmsh, none)")
    ap.add_argument("--core-size", type=float, default=0, help="--core-size of the volume")
    ap.add_argument("--threads", help="thread counts of native and Gmsh, e.g. 1,2 (0: all cores); default: "
                    "native with the CLI's default (all cores), Gmsh with 1")
    ap.add_argument("--no-wasm", action="store_true")
    ap.add_argument("--chromium", action="store_true", help="also time the wasm build in Chromium")
    ap.add_argument("--chromium-runs", type=int, help="runs in Chromium (implies --chromium; default --wasm-runs)")
    ap.add_argument("--no-gmsh", action="store_true")
    ap.add_argument("--gmsh-python", default="/usr/bin/python3" if os.path.exists("/usr/bin/python3") else sys.executable)
    ap.add_argument("--json", help="write all measurements here")
    a = ap.parse_args()
    threads = parse_threads(a.threads)
    chromium_runs = a.chromium_runs if a.chromium_runs is not None else (a.wasm_runs if a.chromium else 0)
    path = a.file if os.path.exists(a.file) else os.path.join(a.data, a.file)
    if not os.path.exists(path):
        print(f"missing input {path}", file=sys.stderr)
        return 1
    what = "full pipeline (volume)" if a.volume else "surface remeshing"
    res = dict(file=os.path.basename(path), size=a.size, volume=a.volume, threads=threads,
               machine_start=benchutil.machine())
    print(f"{res['file']} h = {a.size:g}, {what}; {res['machine_start']}", flush=True)
    with tempfile.TemporaryDirectory() as tmp:
        # One run of each variant per round while it has runs left, so that a
        # drift of the (shared) machine's speed weighs on all alike.
        natives = [NativeBench(a, path, tmp, t) for t in (threads or [None])]
        gmshs = [] if a.no_gmsh else [GmshBench(a, path, tmp, t) for t in (threads or [1])]
        nodes = [] if a.no_wasm else [WasmBench(a, path, threads=t) for t in (threads or [1])]
        chromes = [] if a.no_wasm or not chromium_runs else \
            [WasmBench(a, path, chromium=True, threads=t or os.cpu_count()) for t in (threads or [1])]
        plan = [(b, a.runs) for b in natives] + [(g, a.gmsh_runs) for g in gmshs] + \
            [(x, a.wasm_runs) for x in nodes] + [(c, chromium_runs) for c in chromes]
        print(", ".join(b.name for b, _ in plan) + ", alternating:", flush=True)
        for i in range(max(n for _, n in plan)):
            for b, n in plan:
                if i < n:
                    b.run()
        ns = [b.summary() for b in natives]
        gs = [g.summary() for g in gmshs]
        res["native"] = ns[0]
        if gs:
            res["gmsh"] = gs[0]
        if threads:
            res["native_by_threads"] = {str(x["threads"]): x for x in ns}
            res["gmsh_by_threads"] = {str(x["threads"]): x for x in gs}
        ws = [x.summary() for x in nodes]
        if ws:
            res["wasm"] = ws[0]
            if threads:
                res["wasm_by_threads"] = {str(x.threads): w for x, w in zip(nodes, ws)}
        cs = [c.summary() for c in chromes]
        if cs:
            res["chromium"] = cs[0]
            res["chromium_by_threads"] = {str(c.threads): x for c, x in zip(chromes, cs)}
    res["machine_end"] = benchutil.machine()

    n, w, c = res["native"], res.get("wasm"), res.get("chromium")
    g = next((x for x in gs if x["threads"] == 1), None)  # Gmsh with one thread
    gmsh_by = {x["threads"]: x for x in gs if x["ok"]}
    print()
    native_threads = ", ".join(f"{x['threads']}" for x in ns) if threads else f"{os.cpu_count()} (CLI default)"
    print(f"{res['file']} h = {a.size:g}, {what}; threads: native {native_threads}, "
          f"Gmsh {', '.join(str(x['threads']) for x in gs) or '-'}, "
          f"Chromium {', '.join(str(c.threads) for c in chromes) or '-'}, "
          f"Node {', '.join(str(x.threads) for x in nodes) or '-'}; start: {res['machine_start']}; "
          f"end: load {res['machine_end'].rsplit('load average', 1)[-1].strip()}")
    print(f"{'variant':30} {'median s':>9} {'min s':>7} {'max s':>7} {'runs':>4} {'CPU med s':>9} {'peak MB':>7} "
          f"{'triangles':>9} {'tets':>8} {'gamma_k min/mean':>16} {'xGmsh 1T':>8} {'xGmsh =T':>8}")
    table = []

    def row(name, s, t, times, cpu, rss, notes=()):
        """One variant's row: s its summary, t its threads (for the Gmsh with
        the same threads), times its runs' wall seconds; notes go below."""
        if not s or not s.get("ok"):
            print(f"{name:30} FAILED: {(s or {}).get('error')}")
            table.append(dict(variant=name, ok=False, error=(s or {}).get("error")))
            return
        med = benchutil.median(times)
        g1, gt = g if g and g["ok"] else None, gmsh_by.get(t)
        x1 = g1["median_seconds"] / med if g1 else None
        xt = gt["median_seconds"] / med if gt else None
        table.append(dict(variant=name, ok=True, threads=t, median_seconds=med, median_cpu_seconds=cpu,
                          peak_mb=rss, tets=s.get("tets"), speedup_vs_gmsh_1t=x1, speedup_vs_gmsh_same_t=xt))
        q = s["quality"]
        print(f"{name:30} {med:9.3f} {min(times):7.3f} {max(times):7.3f} {len(times):4d} "
              + (f"{cpu:9.3f}" if cpu is not None else f"{'-':>9}")
              + (f" {rss:7.0f}" if rss is not None else f" {'-':>7}")
              + f" {s['triangles']:9d} " + (f"{s['tets']:8d}" if a.volume and s.get("tets") is not None else f"{'-':>8}")
              + f" {q['min']:9.3f}/{q['mean']:.4f}"
              + "".join(f" {x:8.2f}" if x else f" {'-':>8}" for x in (x1, xt)))
        for note in notes:
            print(f"{'':30}   {note}")

    for x in ns:
        t = x["threads"] or os.cpu_count()
        label = f"vesselmesh native {t}T" if threads else f"vesselmesh native {t}T (default)"
        row(label, x, t, [r["seconds"] for r in x.get("runs", [])], x.get("median_cpu_seconds"), x.get("peak_rss_mb"),
            [f"in-core median {x['median_core_seconds']:.3f} s; stage medians: " +
             ", ".join(f"{k} {v:.2f}" for k, v in x["stage_medians"].items())] +
            (["volume stage medians: " +
              ", ".join(f"{k} {v:.2f}" for k, v in x["volume_stage_medians"].items())]
             if x["volume_stage_medians"] else []) if x["ok"] else ())
    for nd, x in zip(nodes, ws):
        row(f"vesselmesh wasm node {nd.threads}T", x, nd.threads, x.get("seconds", []), x.get("median_cpu_seconds"),
            x.get("process_peak_rss_mb"),
            [f"first run {x['seconds'][0]:.3f} s; Node baseline RSS {x['baseline_rss_mb']:.0f} MB, "
             f"instantiate {x['instantiate_seconds']:.2f} s; {x['node']}; ran on {x.get('threads', 1)} thread(s)"
             + (f" ({x['threads_note']})" if x.get("threads_note") else "")] if x.get("ok") else ())
    for ch, x in zip(chromes, cs):
        row(f"vesselmesh wasm chrome {ch.threads}T", x, ch.threads, x.get("seconds", []), None, x.get("peak_js_heap_mb"),
            [f"first run {x['seconds'][0]:.3f} s; {x.get('browser', '')}; ran on {x.get('threads')} thread(s)"
             + (f" ({x['threads_note']})" if x.get("threads_note") else "")
             + "; no CPU time; peak MB = the page's JS heap"] if x.get("ok") else ())
    for x in gs:
        row(f"Gmsh 4.8 {x['threads']}T (stage sum)", x, x["threads"], [r["seconds"]["total"] for r in x.get("runs", [])],
            x.get("median_cpu_seconds"), x.get("peak_rss_mb"),
            [f"process median {x['median_process_seconds']:.2f} s; stage medians: " +
             ", ".join(f"{k} {v:.2f}" for k, v in x["stage_medians"].items())] +
            (["tets / gamma_t min / mean per run: " + "; ".join(
                f"{r['tets']} / {r['gamma_t']['min']:.3f} / {r['gamma_t']['mean']:.3f}" for r in x["runs"])]
             if a.volume else []) if x["ok"] else ())
    res["table"] = table
    print()
    ratios = {}

    def native_ok(x):
        return x["ok"] and (not a.volume or x["tets"] > 0)

    if not threads:
        # Issue 3 and the volume issue: native (all cores) against Gmsh on one thread.
        if n["ok"] and g and g.get("ok"):
            ratios["gmsh_over_native"] = g["median_seconds"] / n["median_seconds"]
            ok = ratios["gmsh_over_native"] >= TARGET_GMSH_RATIO
            verdict = ("met" if ok else "NOT met") if native_ok(n) else \
                "not comparable: vesselmesh wrote no tetrahedra"
            ratios["gmsh_over_native_cpu"] = g["median_cpu_seconds"] / n["median_cpu_seconds"]
            print(f"Gmsh / native = {ratios['gmsh_over_native']:.2f}x wall, "
                  f"{ratios['gmsh_over_native_cpu']:.2f}x CPU (target >= {TARGET_GMSH_RATIO}x): {verdict}")
        if n["ok"] and w and w.get("ok"):
            ratios["wasm_over_native"] = w["median_seconds"] / n["median_seconds"]
            ok = ratios["wasm_over_native"] <= TARGET_WASM_RATIO
            ratios["wasm_over_native_cpu"] = w["median_cpu_seconds"] / n["median_cpu_seconds"]
            print(f"wasm / native = {ratios['wasm_over_native']:.2f}x wall, "
                  f"{ratios['wasm_over_native_cpu']:.2f}x CPU (target <= {TARGET_WASM_RATIO}x): "
                  f"{'met' if ok else 'NOT met'} (judged on wall time)")
        if n["ok"] and c and c.get("ok"):
            ratios["chromium_over_native"] = c["median_seconds"] / n["median_seconds"]
            ok = ratios["chromium_over_native"] <= TARGET_WASM_RATIO
            print(f"wasm in Chromium / native = {ratios['chromium_over_native']:.2f}x wall "
                  f"(target <= {TARGET_WASM_RATIO}x): {'met' if ok else 'NOT met'}")
    else:
        # Issue 22: native on T threads against Gmsh on T threads (and on one).
        for x in ns:
            t, gt = x["threads"], gmsh_by.get(x["threads"])
            if not x["ok"] or not gt:
                continue
            r = ratios[f"gmsh{t}t_over_native{t}t"] = gt["median_seconds"] / x["median_seconds"]
            rc = ratios[f"gmsh{t}t_over_native{t}t_cpu"] = gt["median_cpu_seconds"] / x["median_cpu_seconds"]
            # The targets are against Gmsh on one thread.
            r1 = ratios[f"gmsh1t_over_native{t}t"] = g["median_seconds"] / x["median_seconds"] \
                if g and g["ok"] else None
            target = TARGET_GMSH_RATIO_BY_THREADS.get(t)
            verdict = "" if target is None or r1 is None else \
                f" (target >= {target}x, the whole run in {g['median_seconds'] / target:.2f} s): " + (
                    ("met" if r1 >= target else "NOT met") if native_ok(x) else
                    "not comparable: vesselmesh wrote no tetrahedra")
            also = f"; Gmsh 1T / native {t}T = {r1:.2f}x" if t != 1 and r1 is not None else ""
            print(f"Gmsh {t}T / native {t}T = {r:.2f}x wall, {rc:.2f}x CPU{also}{verdict}")
            split = stage_split(x, gt)
            if split:
                ratios[f"stages{t}t"] = split
                print(f"  stages on {t}T, ours / Gmsh's: surface {split['surface'][0]:.2f} / "
                      f"{split['surface'][1]:.2f} s ({split['surface'][1] / split['surface'][0]:.2f}x), "
                      f"volume {split['volume'][0]:.2f} / {split['volume'][1]:.2f} s "
                      f"({split['volume'][1] / split['volume'][0]:.2f}x; Gmsh's is HXT), "
                      f"the rest of our run {split['rest']:.2f} s")
        def against_native(label, runners, results):
            """(T, wasm / native on T threads, result) of each wasm variant
            that ran (the threaded core; T = 1: the single-threaded one)."""
            for runner, x in zip(runners, results):
                nt = next((y for y in ns if y["threads"] == runner.threads and y["ok"]), None)
                if nt and x.get("ok"):
                    t = runner.threads
                    r = ratios[f"{label}{t}t_over_native{t}t"] = x["median_seconds"] / nt["median_seconds"]
                    yield t, r, x

        for t, r, x in against_native("node", nodes, ws):
            if t == 1:
                ratios["wasm_over_native1t"] = r
            print(f"Node {t}T / native {t}T = {r:.2f}x wall; Node ran on {x.get('threads', 1)} thread(s)")
        for t, r, x in against_native("chromium", chromes, cs):
            ok = r <= TARGET_CHROMIUM_RATIO
            print(f"Chromium {t}T / native {t}T = {r:.2f}x wall (target <= {TARGET_CHROMIUM_RATIO}x): "
                  f"{'met' if ok else 'NOT met'}; the page ran on {x.get('threads')} thread(s)")
    if n["ok"] and a.volume:
        def edge(e):
            return f" (median tetrahedron edge {e / a.size:.2f} h)" if e else ""
        print(f"vesselmesh wrote {n['tets']} tetrahedra{edge(n.get('median_tet_edge'))}" +
              (f"; Gmsh {g['runs'][0]['tets']}{edge(g['runs'][0].get('median_tet_edge'))}"
               if g and g.get("ok") else ""))
        print("Like for like: the same surface size and about the same tetrahedra; Gmsh's volume is "
              "coarser than h, so --core-size (h x Gmsh's median edge / h) matches it.")
    res["ratios"] = ratios
    if a.json:
        os.makedirs(os.path.dirname(os.path.abspath(a.json)), exist_ok=True)
        with open(a.json, "w") as f:
            json.dump(res, f, indent=1)
    return 0 if all(x["ok"] for x in ns) else 1


if __name__ == "__main__":
    sys.exit(main())
