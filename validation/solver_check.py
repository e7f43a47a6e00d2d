#!/usr/bin/env python3
"""Solver check: the meshes of the real surfaces in ../shared/data/vascular
(read in place, never copied) run in the solvers CFD users would use them
with, Debian's OpenFOAM (v1912) and FEniCS (dolfinx 0.5).

- OpenFOAM: every STL file meshed with --prisms (the layers' prisms kept,
  as a finite-volume solver wants them) into vesselmesh's own
  constant/polyMesh, in metres (--output-units m); `checkMesh` must report no
  failed check and no severely non-orthogonal face (> 70 degrees). The
  bifurcation also goes through MSH 2.2 + `gmshToFoam` (the same mesh, the
  same counts and checks), and is meshed again with a vessel wall (three
  cell zones, the lumen / wall interface a face zone, `outer_wall` a wall). `simpleFoam` (laminar, SIMPLE residual control p
  1e-5, U 1e-6) must converge within 1,000 iterations on the bifurcation
  and the open abdominal aorta: fixed uniform inflow normal to the inlet,
  fixed pressure 0 on the outlets, no slip on the wall, blood's kinematic
  viscosity; the outlets' flow rates (postProcess flowRatePatch) must add
  up to the inlet's within 0.1%.
- Grid convergence (Celik et al. 2008, validation/gci.py, its self-test
  run first): the bifurcation's mesh family (--family 3, ratio 1.5, the
  flags above), each member through simpleFoam with the base mesh's
  inflow, parabolic at Re 300 (no singular rim where a plug inflow meets
  the wall); all must converge; the pressure drop (area-weighted mean of p on
  the inlet minus that on the outlets, 0 there) must approach a limit
  monotonically, 0 < (phi2 - phi1) / (phi3 - phi2) < 1 (1 = finest), with
  GCI_fine21 < 5%. --no-family skips it.
- FEniCS: the bifurcation meshed with split prisms (tetrahedra only, which
  dolfinx reads) into MSH 4.1, read by dolfinx.io.gmshio (model_to_mesh of
  the file opened by the gmsh module: read_from_msh of Debian's 0.5.2 is
  broken); its cell and facet
  tags must carry the physical groups' ids; a Poisson problem (1 on the
  inlet, 0 on the outlets, insulated wall) must have its solution within
  [0 - eps, 1 + eps] (maximum principle).

usage: solver_check.py --data DIR --vesselmesh PATH [--files F ...]
                       [--keep DIR] [--no-simplefoam] [--no-family] [--no-fenics]
                       [--reynolds RE]
Exit status 0 when every check passes. Prints a table of the numbers.
"""
import argparse
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

FOAM_BASHRC = "/usr/share/openfoam/etc/bashrc"

# Per file: the unit of its numbers (data README) and what a closed surface
# needs to have openings (as validate_real_data.py meshes them).
FILES = {
    "abdominal-aorta-closed.stl": ["--units", "mm", "--clip", "auto"],
    "abdominal-aorta-open.stl": ["--units", "mm"],
    "aortic-arch.stl": ["--units", "cm"],
    "bifurcation.stl": ["--units", "cm"],
    "carotid-metres.stl": ["--units", "m"],
    "coronary-closed-ascii.stl": ["--units", "mm", "--keep-caps", "--clip", "auto"],
    "femoral-bypass.stl": ["--units", "cm"],
}
# The OpenFOAM preset's choices: prisms kept, metres; the default size (20
# edges around the local circumference).
FOAM_FLAGS = ["--prisms", "--output-units", "m"]
SIMPLEFOAM_FILES = ["bifurcation.stl", "abdominal-aorta-open.stl"]
NU_BLOOD = 3.3e-6  # m^2/s: 3.5 mPa s / 1060 kg/m^3
# Of the inflow, on the inlet's equivalent diameter: a resting mean flow
# (0.30 m/s into the carotid-sized bifurcation, 0.13 m/s into the aorta).
# Both converge in about 210 iterations at 600 (about 190 at 100).
REYNOLDS = 600
FENICS_FILE = "bifurcation.stl"
EPS = 1e-3
# Grid convergence study (Celik et al. 2008, validation/gci.py): the
# bifurcation's mesh family (--family 3 --ratio FAMILY_RATIO, the flags of
# its simpleFoam case), each member through simpleFoam at the base case's
# inflow; the quantity is the pressure drop from the inlet to the outlets.
FAMILY_FILE = "bifurcation.stl"
FAMILY_MEMBERS = 3
# 1.5: at 1.4 the default bifurcation's three members are not yet in the
# asymptotic range for the drop (its changes, 0.4-0.5 %, grow from one
# member to the next: measured 2026-12, eps21/eps32 1.24); at 1.5 they
# shrink (0.90) within the same time.
FAMILY_RATIO = 1.5
GCI_MAX = 0.05  # GCI_fine21 of the pressure drop
# The study's inflow: parabolic (parabolic_inflow), at this Reynolds number
# on the inlet's diameter (its peak speed twice the mean: the steady flow of
# the checks' Re 600 with a plug inflow).
FAMILY_REYNOLDS = 300
RHO_BLOOD = 1060.0  # kg/m^3: kinematic pressure (m^2/s^2) to Pa

failures = []


def check(name, ok, what):
    print(f"  [{'ok' if ok else 'FAIL'}] {name}: {what}", flush=True)
    if not ok:
        failures.append(f"{name}: {what}")
    return ok


def foam(cmd, case, log):
    """Runs an OpenFOAM command in `case` in a subshell that sourced
    OpenFOAM's bashrc; its output goes to `log`. Returns (exit, seconds)."""
    t = time.time()
    with open(log, "w") as f:
        r = subprocess.run(["bash", "-c", f"source {FOAM_BASHRC} >/dev/null 2>&1; {cmd}"],
                           cwd=case, stdout=f, stderr=subprocess.STDOUT)
    return r.returncode, time.time() - t


def header(cls, obj, location):
    return ("FoamFile\n{\n    version     2.0;\n    format      ascii;\n"
            f"    class       {cls};\n    location    \"{location}\";\n    object      {obj};\n}}\n\n")


def write(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(text)


def check_mesh(name, case):
    """checkMesh on `case`: no failed check, no face above 70 degrees of
    non-orthogonality. Returns the numbers it reports."""
    code, secs = foam("checkMesh", case, os.path.join(case, "checkMesh.log"))
    text = open(os.path.join(case, "checkMesh.log")).read()
    n = {"seconds": secs}
    m = re.search(r"cells:\s+(\d+)", text)
    n["cells"] = int(m.group(1)) if m else -1
    m = re.search(r"Mesh non-orthogonality Max: ([\d.eE+-]+) average: ([\d.eE+-]+)", text)
    n["non_ortho_max"], n["non_ortho_mean"] = (float(m.group(1)), float(m.group(2))) if m else (-1, -1)
    m = re.search(r"Max skewness = ([\d.eE+-]+)", text)
    n["skewness"] = float(m.group(1)) if m else -1
    m = re.search(r"Number of severely non-orthogonal \(> 70 degrees\) faces: (\d+)", text)
    n["severe"] = int(m.group(1)) if m else 0
    m = re.search(r"Failed (\d+) mesh checks", text)
    n["failed"] = int(m.group(1)) if m else 0
    ok = code == 0 and "Mesh OK." in text
    check(name, ok and n["failed"] == 0,
          f"checkMesh: {n['cells']} cells, {'Mesh OK' if ok else 'failed ' + str(n['failed'])} "
          f"(exit {code}, {secs:.1f} s)")
    check(name, n["severe"] == 0 and 0 <= n["non_ortho_max"] <= 70,
          f"non-orthogonality max {n['non_ortho_max']:.1f} deg (mean {n['non_ortho_mean']:.1f}), "
          f"{n['severe']} faces > 70 deg; max skewness {n['skewness']:.2f}")
    return n


def read_patch_faces(case, patch):
    """The points and faces of one boundary patch of a polyMesh (ASCII)."""
    poly = os.path.join(case, "constant", "polyMesh")

    def body(name):
        text = open(os.path.join(poly, name)).read()
        return text[text.index("\n}\n") + 3:]

    b = body("boundary")
    m = re.search(r"\b" + re.escape(patch) + r"\s*\{[^}]*?nFaces\s+(\d+);[^}]*?startFace\s+(\d+);", b)
    n, start = int(m.group(1)), int(m.group(2))
    pts = [tuple(map(float, p)) for p in
           re.findall(r"\(([-\d.eE+]+) ([-\d.eE+]+) ([-\d.eE+]+)\)", body("points"))]
    faces = [list(map(int, f.split())) for f in re.findall(r"\d+\(([\d ]+)\)", body("faces"))]
    return pts, faces[start:start + n]


def patch_area(case, patch):
    pts, faces = read_patch_faces(case, patch)
    area = 0.0
    for f in faces:
        p0 = pts[f[0]]
        for a, b in zip(f[1:-1], f[2:]):
            u = [pts[a][i] - p0[i] for i in range(3)]
            v = [pts[b][i] - p0[i] for i in range(3)]
            c = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
            area += 0.5 * math.sqrt(sum(x * x for x in c))
    return area


def patches(case):
    text = open(os.path.join(case, "constant", "polyMesh", "boundary")).read()
    text = text[text.index("\n}\n") + 3:]
    return re.findall(r"^\s*([A-Za-z_][\w.-]*)\s*\n\s*\{\s*\n\s*type\s+(\w+);", text, re.M)


def parabolic_inflow(case, speed):
    """A Poiseuille-like inflow on the inlet: per face, 2 U (1 - d^2 / R^2)
    (d the face centre's distance to the inlet's centroid, R the radius of
    the disc of its area, 0 beyond R), scaled so that its flow is U times the
    inlet's area. Unlike a plug profile it has no singular corner where it
    meets the no-slip wall, whose entrance loss converges slowly with the
    mesh. Returns the faces' normal speeds (m/s, inward)."""
    pts, faces = read_patch_faces(case, "inlet")
    centres, areas = [], []
    for f in faces:
        p0, a, c = pts[f[0]], 0.0, [0.0, 0.0, 0.0]
        for i, j in zip(f[1:-1], f[2:]):
            u = [pts[i][k] - p0[k] for k in range(3)]
            v = [pts[j][k] - p0[k] for k in range(3)]
            t = 0.5 * math.sqrt(sum(x * x for x in (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                                                   u[0] * v[1] - u[1] * v[0])))
            for k in range(3):
                c[k] += t * (p0[k] + pts[i][k] + pts[j][k]) / 3
            a += t
        centres.append([x / a for x in c])
        areas.append(a)
    area = sum(areas)
    centroid = [sum(a * c[k] for a, c in zip(areas, centres)) / area for k in range(3)]
    r2 = area / math.pi
    shape = [max(0.0, 1 - sum((c[k] - centroid[k]) ** 2 for k in range(3)) / r2) for c in centres]
    scale = speed * area / sum(a * w for a, w in zip(areas, shape))
    return [scale * w for w in shape]


def set_up_simplefoam(case, speed, profile=False):
    """The 0/ fields and system/ of a laminar simpleFoam run: inflow normal
    to the inlet, uniform at `speed` or (profile) parabolic_inflow's of the
    same flow; p = 0 on the outlets; no slip on the wall."""
    names = [p for p, _ in patches(case)]
    outlets = [p for p in names if p.startswith("outlet")]
    inflow = f"uniform {-speed:.6g}"
    if profile:
        v = parabolic_inflow(case, speed)
        inflow = f"nonuniform List<scalar> {len(v)} (" + " ".join(f"{-x:.8g}" for x in v) + ")"
    u_bc = {"inlet": f"type surfaceNormalFixedValue; refValue {inflow};",
            "wall": "type noSlip;"}
    p_bc = {"inlet": "type zeroGradient;", "wall": "type zeroGradient;"}
    for o in outlets:
        u_bc[o] = "type inletOutlet; inletValue uniform (0 0 0); value uniform (0 0 0);"
        p_bc[o] = "type fixedValue; value uniform 0;"

    def field(cls, obj, dims, internal, bcs):
        s = header(cls, obj, "0") + f"dimensions      {dims};\n\ninternalField   {internal};\n\n"
        s += "boundaryField\n{\n"
        for p in names:
            s += f"    {p}\n    {{\n        {bcs[p]}\n    }}\n"
        return s + "}\n"

    write(os.path.join(case, "0", "U"), field("volVectorField", "U", "[0 1 -1 0 0 0 0]",
                                               "uniform (0 0 0)", u_bc))
    write(os.path.join(case, "0", "p"), field("volScalarField", "p", "[0 2 -2 0 0 0 0]",
                                               "uniform 0", p_bc))

    def dictionary(location, obj, body):
        write(os.path.join(case, location, obj), header("dictionary", obj, location) + body)

    dictionary("constant", "transportProperties",
               f"transportModel  Newtonian;\n\nnu              {NU_BLOOD};\n")
    dictionary("constant", "turbulenceProperties", "simulationType  laminar;\n")
    dictionary("system", "controlDict",
               "application     simpleFoam;\nstartFrom       startTime;\nstartTime       0;\n"
               "stopAt          endTime;\nendTime         1000;\ndeltaT          1;\n"
               "writeControl    timeStep;\nwriteInterval   1000;\npurgeWrite      0;\n"
               "writeFormat     ascii;\nwritePrecision  8;\ntimeFormat      general;\n"
               "timePrecision   6;\nrunTimeModifiable false;\n")
    dictionary("system", "fvSchemes",
               "ddtSchemes { default steadyState; }\n"
               "gradSchemes { default Gauss linear; }\n"
               "divSchemes\n{\n    default none;\n    div(phi,U) bounded Gauss linearUpwind grad(U);\n"
               "    div((nuEff*dev2(T(grad(U))))) Gauss linear;\n}\n"
               "laplacianSchemes { default Gauss linear limited corrected 0.5; }\n"
               "interpolationSchemes { default linear; }\n"
               "snGradSchemes { default limited corrected 0.5; }\n")
    dictionary("system", "fvSolution",
               "solvers\n{\n"
               "    p { solver GAMG; smoother GaussSeidel; tolerance 1e-8; relTol 0.05; }\n"
               "    U { solver smoothSolver; smoother symGaussSeidel; tolerance 1e-9; relTol 0.1; }\n"
               "}\n"
               "SIMPLE\n{\n    nNonOrthogonalCorrectors 1;\n    consistent yes;\n"
               "    residualControl { p 1e-5; U 1e-6; }\n}\n"
               "relaxationFactors { equations { U 0.9; \".*\" 0.9; } }\n")


def run_simplefoam(name, case, reynolds, speed=None, profile=False):
    """simpleFoam on `case` at `reynolds` on its inlet's equivalent diameter,
    or at the given inflow `speed` (m/s) when one is given; a parabolic
    inflow of that mean speed with `profile` (set_up_simplefoam)."""
    area = patch_area(case, "inlet")
    diameter = math.sqrt(4 * area / math.pi)
    speed = speed or reynolds * NU_BLOOD / diameter
    reynolds = speed * diameter / NU_BLOOD
    set_up_simplefoam(case, speed, profile)
    code, secs = foam("simpleFoam", case, os.path.join(case, "simpleFoam.log"))
    text = open(os.path.join(case, "simpleFoam.log")).read()
    m = re.search(r"SIMPLE solution converged in (\d+) iterations", text)
    its = int(m.group(1)) if m else None
    last = re.findall(r"^Time = (\d+)$", text, re.M)
    check(name, code == 0 and its is not None and its <= 1000,
          f"simpleFoam (laminar, {'parabolic' if profile else 'uniform'} inflow {speed * 1000:.2f} mm/s normal to the inlet of "
          f"{diameter * 1000:.2f} mm, Re {reynolds:g}): "
          + (f"converged in {its} iterations" if its else
             f"not converged (exit {code}, {last[-1] if last else 0} iterations)")
          + f", {secs:.1f} s")
    if its:
        # Mass balance: what comes in at the inlet leaves by the outlets.
        flows = {}
        for patch in [p for p, _ in patches(case) if p == "inlet" or p.startswith("outlet")]:
            log = os.path.join(case, f"flowRate-{patch}.log")
            foam(f"postProcess -func 'flowRatePatch(name={patch})' -latestTime", case, log)
            m = re.search(r"sum\(" + re.escape(patch) + r"\) of phi = (\S+)", open(log).read())
            flows[patch] = float(m.group(1)) if m else float("nan")
        q_in = -flows.get("inlet", float("nan"))
        q_out = sum(q for p, q in flows.items() if p != "inlet")
        check(name, q_in > 0 and abs(q_out - q_in) <= 1e-3 * q_in and
              abs(q_in - speed * area) <= 0.01 * speed * area,
              f"flow rate in {q_in * 6e7:.4g} ml/min (speed x inlet area "
              f"{speed * area * 6e7:.4g}), out {q_out * 6e7:.4g} ml/min, split " +
              ", ".join(f"{p} {100 * q / q_in:.1f}%" for p, q in flows.items() if p != "inlet"))
    return dict(iterations=its, seconds=secs, speed=speed, diameter=diameter)


def pressure_drop(case):
    """The pressure drop of a converged case (latest time): the area-weighted
    mean of the kinematic pressure p over the inlet minus its area-weighted
    mean over all outlets together (postProcess patchAverage). The outlets
    hold p = 0 (fixed value), so their mean is 0 and any weighting gives the
    same drop. Returns (drop, inlet mean, outlet mean) in m^2/s^2."""
    names = [p for p, _ in patches(case) if p == "inlet" or p.startswith("outlet")]
    log = os.path.join(case, "patchAverage.log")
    funcs = " ".join(f"patchAverage(name={p},p)" for p in names)
    foam(f"postProcess -funcs '({funcs})' -latestTime", case, log)
    found = {m.group(2): (float(m.group(1)), float(m.group(3))) for m in re.finditer(
        r"total area\s+=\s+(\S+)\s+areaAverage\((\S+)\) of p = (\S+)", open(log).read())}
    if set(found) != set(names):
        return float("nan"), float("nan"), float("nan")
    outlets = [found[p] for p in names if p != "inlet"]
    p_out = sum(a * p for a, p in outlets) / sum(a for a, _ in outlets)
    p_in = found["inlet"][1]
    return p_in - p_out, p_in, p_out


def family_study(args, path, tmp, rows):
    """A grid convergence study (Celik et al. 2008, validation/gci.py) of
    the pressure drop: the mesh family of `path` (FAMILY_MEMBERS members,
    sizes divided by FAMILY_RATIO from one to the next, the flags of its
    simpleFoam case), each member through simpleFoam with the same boundary
    conditions (the inflow speed of member 0, the base mesh, at the chosen
    Reynolds number); every member must converge, the pressure drops must
    approach a limit monotonically (0 < (phi2 - phi1) / (phi3 - phi2) < 1,
    1 = finest) and GCI_fine21 must stay below GCI_MAX."""
    import json
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import gci
    name = os.path.basename(path) + " (family)"
    bad = gci.self_test(verbose=False)
    check(name, not bad, "gci.py self-test (Celik et al. 2008 Table 1, phi0 + C h^2): "
          + ("passed" if not bad else "; ".join(bad)))
    start = time.time()
    base = os.path.join(tmp, "bif-family")
    r, secs = vesselmesh(args, path, base + "/", FILES[os.path.basename(path)] + FOAM_FLAGS +
                         ["--format", "foam", "--family", str(FAMILY_MEMBERS),
                          "--ratio", str(FAMILY_RATIO)])
    if not check(name, r.returncode == 0, f"{FAMILY_MEMBERS} members meshed (ratio {FAMILY_RATIO}) in "
                 f"{secs:.1f} s {r.stderr.strip()}"):
        return
    table = json.load(open(base + "_family.json"))
    fam, unit = table["rows"], table["unit"]
    speed, results = None, []
    for row in fam:
        k = row["member"]
        case = os.path.join(tmp, f"bif-family_{k}")
        label = f"{name} member {k}"
        print(f"  member {k}: {row['cells']} cells ({row['tetrahedra']} tetrahedra, {row['prisms']} prisms, "
              f"{row['layers']} layers), h {row['h']:.5g} {unit}, "
              f"ratio {row['ratio']:.3f}", flush=True)
        n = check_mesh(label, case)
        if speed is None:
            # The base mesh's inflow speed (that of the file's own case), kept
            # for the finer members: the same boundary conditions.
            diameter = math.sqrt(4 * patch_area(case, "inlet") / math.pi)
            speed = FAMILY_REYNOLDS * NU_BLOOD / diameter
        s = run_simplefoam(label, case, args.reynolds, speed, profile=True)
        drop, p_in, p_out = pressure_drop(case) if s["iterations"] else (float("nan"),) * 3
        print(f"  member {k}: pressure drop {drop:.7g} m^2/s^2 ({drop * RHO_BLOOD:.3f} Pa): inlet mean "
              f"{p_in:.7g}, outlets' mean {p_out:.3g}", flush=True)
        results.append(dict(member=k, h=row["h"], cells=n["cells"], drop=drop, **s))
        rows.append((name, f"member {k}: simpleFoam + pressure drop", f"{n['cells']} cells, h {row['h']:.4g}",
                     f"{s['iterations'] or 'NOT'} iterations, dp {drop:.6g} m^2/s^2 "
                     f"({drop * RHO_BLOOD:.2f} Pa)", f"{s['seconds']:.1f} s"))
    converged = all(x["iterations"] for x in results) and len(results) == FAMILY_MEMBERS
    check(name, converged, "every member converged: "
          + ", ".join(f"{x['iterations'] or 'NOT'}" for x in results) + " iterations")
    if not converged or len(results) != 3:
        return
    fine = results[::-1]  # 1 = finest
    g = gci.gci([x["h"] for x in fine], [x["drop"] for x in fine])
    ratio = g["eps21"] / g["eps32"]
    print(f"  GCI (Celik et al. 2008): phi1..3 = {fine[0]['drop']:.7g}, {fine[1]['drop']:.7g}, "
          f"{fine[2]['drop']:.7g} m^2/s^2; r21 {g['r21']:.4f}, r32 {g['r32']:.4f}; "
          f"eps21 {g['eps21']:.4g}, eps32 {g['eps32']:.4g} (eps21/eps32 {ratio:.3f}); "
          f"s {g['s']:+.0f}; apparent order p {g['p']:.3f} ({g['iterations']} fixed-point iterations"
          f"{'' if g['converged'] else ', NOT converged'}); phi_ext21 {g['phi_ext21']:.7g} "
          f"({g['phi_ext21'] * RHO_BLOOD:.3f} Pa); e_a21 {100 * g['e_a21']:.3f}%, "
          f"e_ext21 {100 * g['e_ext21']:.3f}%, GCI_fine21 {100 * g['gci_fine21']:.3f}%", flush=True)
    check(name, g["monotone"],
          f"pressure drops approach a limit: (phi2 - phi1) / (phi3 - phi2) = {ratio:.3f} in (0, 1) "
          f"({', '.join(f'{x:.6g}' for x in (fine[0]['drop'], fine[1]['drop'], fine[2]['drop']))}, "
          f"finest first)")
    check(name, g["gci_fine21"] < GCI_MAX,
          f"GCI_fine21 of the pressure drop {100 * g['gci_fine21']:.2f}% < {100 * GCI_MAX:g}% "
          f"(p {g['p']:.2f}, phi_ext21 {g['phi_ext21']:.6g}"
          + ("" if g["monotone"] else "; not monotone: the estimate does not hold") + ")")
    drops = ", ".join(f"{x['drop']:.5g}" for x in fine)
    rows.append((name, "GCI (Celik et al. 2008) of the pressure drop",
                 f"r21 {g['r21']:.3f}, r32 {g['r32']:.3f}",
                 f"dp {drops} (fine to coarse); p {g['p']:.2f}, "
                 f"phi_ext {g['phi_ext21']:.5g}, e_a21 {100 * g['e_a21']:.2f}%, "
                 f"GCI_fine21 {100 * g['gci_fine21']:.2f}%",
                 f"{time.time() - start:.1f} s in all"))


def wall_case(args, path, tmp, rows):
    """With a vessel wall and the viscous layer tagged: three cell zones, the
    lumen / vessel-wall interface a face zone of internal faces (no patch),
    the outer surface a wall patch; checkMesh passes."""
    name = os.path.basename(path) + " (vessel wall)"
    case = os.path.join(tmp, "bifurcation-wall")
    shutil.rmtree(case, ignore_errors=True)
    r, secs = vesselmesh(args, path, case + "/", FILES[os.path.basename(path)] + FOAM_FLAGS +
                         ["--format", "foam", "--wall-thickness", "0.1", "--tag-layer"])
    if not check(name, r.returncode == 0, f"meshed in {secs:.1f} s {r.stderr.strip()}"):
        return
    kinds = dict(patches(case))
    check(name, "wall" not in kinds and kinds.get("outer_wall") == "wall" and
          kinds.get("wall_inlet") == "patch",
          f"boundary: {', '.join(f'{p} ({t})' for p, t in kinds.items())}")
    n = check_mesh(name, case)
    text = open(os.path.join(case, "checkMesh.log")).read()
    zones = re.findall(r"^\s+(lumen|boundary_layer|vessel_wall)\s+\d+", text, re.M)
    face_zone = re.search(r"^\s+wall\s+(\d+)\s+\d+\s+ok", text, re.M)
    check(name, sorted(zones) == ["boundary_layer", "lumen", "vessel_wall"] and face_zone,
          f"checkMesh reads the cell zones {zones} and the face zone wall "
          f"({face_zone.group(1) if face_zone else 'missing'} faces)")
    rows.append((name, "native polyMesh", f"{n['cells']} cells",
                 f"non-ortho max {n['non_ortho_max']:.1f} mean {n['non_ortho_mean']:.1f}, "
                 f"skew {n['skewness']:.2f}", f"mesh {secs:.1f} s, check {n['seconds']:.1f} s"))


def vesselmesh(args, path, out, flags):
    t = time.time()
    r = subprocess.run([args.vesselmesh, "mesh", path, "-o", out, "--quiet"] + flags,
                       capture_output=True, text=True)
    return r, time.time() - t


def fenics_check(args, path, tmp, rows):
    name = os.path.basename(path)
    out = os.path.join(tmp, "fenics.msh")
    r, secs = vesselmesh(args, path, out, FILES[name])
    if not check(name, r.returncode == 0, f"FEniCS mesh (split prisms, MSH 4.1) {secs:.1f} s "
                 f"{r.stderr.strip()}"):
        return
    code = FENICS_SCRIPT
    t = time.time()
    p = subprocess.run(["/usr/bin/python3", "-c", code, out], capture_output=True, text=True)
    secs = time.time() - t
    lines = [ln for ln in p.stdout.splitlines() if ln.startswith("RESULT ")]
    if not check(name, p.returncode == 0 and bool(lines), f"dolfinx ran (exit {p.returncode})"
                 + ("" if p.returncode == 0 else " " + p.stderr.strip()[-800:])):
        return
    res = dict(kv.split("=", 1) for kv in lines[-1].split()[1:])
    check(name, res["cell_tags"] == res["want_cells"],
          f"dolfinx cell tags {res['cell_tags']} (physical volumes {res['want_cells']})")
    check(name, res["facet_tags"] == res["want_facets"],
          f"dolfinx facet tags {res['facet_tags']} (physical surfaces {res['want_facets']})")
    lo, hi = float(res["min"]), float(res["max"])
    check(name, -EPS <= lo and hi <= 1 + EPS and float(res["inlet_mean"]) > 0.999,
          f"Poisson (1 on inlet, 0 on outlets): solution in [{lo:.3g}, {hi:.7g}] "
          f"({res['cells']} cells, {res['dofs']} dofs, {secs:.1f} s)")
    rows.append((name, "dolfinx Poisson", f"{res['cells']} cells", f"u in [{lo:.2g}, {hi:.6f}]",
                 f"{secs:.1f} s"))


# Runs in its own process (dolfinx and MPI stay out of this one).
FENICS_SCRIPT = r'''
import sys
import gmsh
import numpy as np
import ufl
from mpi4py import MPI
from petsc4py import PETSc
from dolfinx import fem
from dolfinx.io import gmshio
import dolfinx.fem.petsc

path = sys.argv[1]
# gmshio.read_from_msh of Debian's dolfinx 0.5.2 fails (NameError: msh), so
# the file goes through the gmsh module and gmshio.model_to_mesh, which is
# what read_from_msh does.
gmsh.initialize()
gmsh.option.setNumber("General.Terminal", 0)
gmsh.open(path)
groups = {(d, t): gmsh.model.getPhysicalName(d, t) for d, t in gmsh.model.getPhysicalGroups()}
mesh, cell_tags, facet_tags = gmshio.model_to_mesh(gmsh.model, MPI.COMM_WORLD, 0, gdim=3)
gmsh.finalize()
def show(tags, dim):
    return ",".join(f"{groups[(dim, int(t))]}:{int(t)}" for t in sorted(set(tags.values)))
def want(dim):
    return ",".join(f"{n}:{t}" for (d, t), n in sorted(groups.items()) if d == dim)
ids = {n: t for (d, t), n in groups.items() if d == 2}
V = fem.FunctionSpace(mesh, ("Lagrange", 1))
mesh.topology.create_connectivity(2, 3)
def bc(name, value):
    facets = facet_tags.indices[facet_tags.values == ids[name]]
    dofs = fem.locate_dofs_topological(V, 2, facets)
    return fem.dirichletbc(PETSc.ScalarType(value), dofs, V), dofs
bcs = [bc("inlet", 1.0)] + [bc(n, 0.0) for n in ids if n.startswith("outlet")]
u, v = ufl.TrialFunction(V), ufl.TestFunction(V)
a = ufl.inner(ufl.grad(u), ufl.grad(v)) * ufl.dx
L = fem.Constant(mesh, PETSc.ScalarType(0)) * v * ufl.dx
problem = fem.petsc.LinearProblem(a, L, bcs=[b for b, _ in bcs], petsc_options={
    "ksp_type": "cg", "pc_type": "gamg", "ksp_rtol": 1e-12})
uh = problem.solve()
x = uh.x.array
print("RESULT", f"cell_tags={show(cell_tags, 3)}", f"want_cells={want(3)}",
      f"facet_tags={show(facet_tags, 2)}", f"want_facets={want(2)}",
      f"min={x.min():.9g}", f"max={x.max():.9g}", f"inlet_mean={x[bcs[0][1]].mean():.9g}",
      f"cells={mesh.topology.index_map(3).size_local}",
      f"dofs={V.dofmap.index_map.size_local}")
'''


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--data", required=True)
    ap.add_argument("--vesselmesh", required=True)
    ap.add_argument("--files", nargs="*")
    ap.add_argument("--keep", help="write the cases here instead of a temporary folder")
    ap.add_argument("--no-simplefoam", action="store_true")
    ap.add_argument("--no-fenics", action="store_true")
    ap.add_argument("--no-family", action="store_true",
                    help="skip the grid convergence study (the mesh family through simpleFoam)")
    ap.add_argument("--reynolds", type=float, default=REYNOLDS,
                    help=f"inflow Reynolds number on the inlet's diameter (default {REYNOLDS})")
    args = ap.parse_args()
    args.vesselmesh = os.path.abspath(args.vesselmesh)
    if not os.path.exists(FOAM_BASHRC) or not shutil.which("checkMesh"):
        print(f"solver_check: OpenFOAM is not installed ({FOAM_BASHRC}); apt-get install openfoam")
        return 1
    files = args.files or sorted(FILES)
    start = time.time()
    tmp = args.keep or tempfile.mkdtemp(prefix="vm-solver-")
    os.makedirs(tmp, exist_ok=True)
    rows = []  # (file, what, size, numbers, time)
    try:
        for name in files:
            path = os.path.join(args.data, name)
            print(f"== {name}", flush=True)
            case = os.path.join(tmp, name.replace(".stl", ""))
            shutil.rmtree(case, ignore_errors=True)
            r, secs = vesselmesh(args, path, case + "/", FILES[name] + FOAM_FLAGS + ["--format", "foam"])
            if not check(name, r.returncode == 0, f"meshed into constant/polyMesh in {secs:.1f} s "
                         + r.stderr.strip()):
                continue
            kinds = dict(patches(case))
            check(name, kinds.get("wall") == "wall" and kinds.get("inlet") == "patch" and
                  all(t == "patch" for p, t in kinds.items() if p.startswith("outlet")),
                  f"boundary: {', '.join(f'{p} ({t})' for p, t in kinds.items())}")
            n = check_mesh(name, case)
            rows.append((name, "native polyMesh", f"{n['cells']} cells",
                         f"non-ortho max {n['non_ortho_max']:.1f} mean {n['non_ortho_mean']:.1f}, "
                         f"skew {n['skewness']:.2f}", f"mesh {secs:.1f} s, check {n['seconds']:.1f} s"))
            if name == "bifurcation.stl":
                # The same mesh through Gmsh's MSH 2.2 and OpenFOAM's gmshToFoam.
                gcase = case + "-gmshToFoam"
                shutil.rmtree(gcase, ignore_errors=True)
                os.makedirs(os.path.join(gcase, "system"))
                for f in ("controlDict", "fvSchemes", "fvSolution"):
                    shutil.copy(os.path.join(case, "system", f), os.path.join(gcase, "system", f))
                msh = os.path.join(tmp, "bifurcation22.msh")
                r, _ = vesselmesh(args, path, msh, FILES[name] + FOAM_FLAGS + ["--msh-version", "2.2"])
                code, _ = foam(f"gmshToFoam {msh}", gcase, os.path.join(gcase, "gmshToFoam.log"))
                if check(name, r.returncode == 0 and code == 0, f"MSH 2.2 read by gmshToFoam (exit {code})"):
                    g = check_mesh(name + " (gmshToFoam)", gcase)
                    check(name, g["cells"] == n["cells"] and
                          abs(g["non_ortho_max"] - n["non_ortho_max"]) < 0.05,
                          f"gmshToFoam's mesh is the native one: {g['cells']} cells, "
                          f"non-orthogonality max {g['non_ortho_max']:.1f}")
                    rows.append((name, "MSH 2.2 + gmshToFoam", f"{g['cells']} cells",
                                 f"non-ortho max {g['non_ortho_max']:.1f} mean "
                                 f"{g['non_ortho_mean']:.1f}, skew {g['skewness']:.2f}",
                                 f"check {g['seconds']:.1f} s"))
            if name == "bifurcation.stl":
                wall_case(args, path, tmp, rows)
            if name in SIMPLEFOAM_FILES and not args.no_simplefoam:
                s = run_simplefoam(name, case, args.reynolds)
                rows.append((name, "simpleFoam laminar", f"{n['cells']} cells",
                             f"{s['iterations'] or 'NOT'} iterations to converge",
                             f"{s['seconds']:.1f} s"))
        if FAMILY_FILE in files and not args.no_simplefoam and not args.no_family:
            print(f"== {FAMILY_FILE}: grid convergence study", flush=True)
            family_study(args, os.path.join(args.data, FAMILY_FILE), tmp, rows)
        if not args.no_fenics and FENICS_FILE in files:
            print(f"== {FENICS_FILE}: FEniCS", flush=True)
            fenics_check(args, os.path.join(args.data, FENICS_FILE), tmp, rows)
    finally:
        if not args.keep:
            shutil.rmtree(tmp, ignore_errors=True)
    print("\n| file | check | size | numbers | time |\n|---|---|---|---|---|")
    for row in rows:
        print("| " + " | ".join(row) + " |")
    print(f"\nsolver check: {time.time() - start:.0f} s, "
          f"{'all passed' if not failures else str(len(failures)) + ' FAILED'}")
    for f in failures:
        print("  FAIL " + f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
