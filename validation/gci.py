#!/usr/bin/env python3
"""Grid Convergence Index (GCI) of a three-mesh study, per

    I. B. Celik, U. Ghia, P. J. Roache, C. J. Freitas, H. Coleman, P. E. Raad,
    "Procedure for Estimation and Reporting of Uncertainty Due to
    Discretization in CFD Applications", J. Fluids Eng. 130(7), 078001 (2008),
    doi:10.1115/1.2960953.

Meshes 1 (finest), 2, 3 (coarsest) with representative sizes h1 < h2 < h3
(in 3D h = (V / N)^(1/3), eq. 1) and a solution value phi_i on each:

    r21 = h2 / h1, r32 = h3 / h2                                (step 2)
    eps21 = phi2 - phi1, eps32 = phi3 - phi2, s = sign(eps32 / eps21)
    p = |ln|eps32 / eps21| + q(p)| / ln r21,
    q(p) = ln((r21^p - s) / (r32^p - s))                        (eqs. 3a-c)
        solved by fixed-point iteration (q = 0 when r21 = r32)
    phi_ext21 = (r21^p phi1 - phi2) / (r21^p - 1)               (eq. 4)
    e_a21 = |(phi1 - phi2) / phi1|                              (eq. 5a)
    e_ext21 = |(phi_ext21 - phi1) / phi_ext21|                  (eq. 5b)
    GCI_fine21 = 1.25 e_a21 / (r21^p - 1)                       (eq. 5c)

`python3 gci.py --self-test` checks the implementation against the first
column of the paper's Table 1 (as printed there, to its digits) and against
a manufactured second-order case phi(h) = phi0 + C h^2 (p = 2 and
phi_ext = phi0 to 1e-6). Exit status 0 when it passes.
"""
import math
import sys


def representative_size(volume, cells, dim=3):
    """h = (V / N)^(1/dim) (Celik et al. eq. 1, uniform cells)."""
    return (volume / cells) ** (1.0 / dim)


def gci(h, phi, safety=1.25, tol=1e-12, max_iter=500):
    """The GCI of three meshes. `h` and `phi` list the meshes finest first
    (h[0] < h[1] < h[2]). Returns a dict: r21, r32, eps21, eps32, s, p,
    iterations, converged (of the fixed-point iteration), phi_ext21,
    phi_ext32, e_a21, e_ext21, gci_fine21, monotone (0 < eps21/eps32 < 1:
    the differences shrink with refinement, of the same sign)."""
    h1, h2, h3 = h
    phi1, phi2, phi3 = phi
    if not h1 < h2 < h3:
        raise ValueError(f"h must grow from the finest to the coarsest mesh: {h}")
    r21, r32 = h2 / h1, h3 / h2
    eps21, eps32 = phi2 - phi1, phi3 - phi2
    if eps21 == 0 or eps32 == 0:
        raise ValueError(f"equal solutions on two meshes, no apparent order: {phi}")
    ratio = eps32 / eps21
    s = 1.0 if ratio > 0 else -1.0
    p = abs(math.log(abs(ratio))) / math.log(r21)  # q = 0: the first guess
    converged, it = False, 0
    for it in range(1, max_iter + 1):
        try:
            q = math.log((r21 ** p - s) / (r32 ** p - s))
        except (ValueError, ZeroDivisionError, OverflowError):
            break
        new = abs(math.log(abs(ratio)) + q) / math.log(r21)
        if abs(new - p) <= tol * max(1.0, abs(new)):
            p, converged = new, True
            break
        p = new
    rp21, rp32 = r21 ** p, r32 ** p
    phi_ext21 = (rp21 * phi1 - phi2) / (rp21 - 1)
    phi_ext32 = (rp32 * phi2 - phi3) / (rp32 - 1)
    e_a21 = abs((phi1 - phi2) / phi1)
    e_ext21 = abs((phi_ext21 - phi1) / phi_ext21)
    return dict(r21=r21, r32=r32, eps21=eps21, eps32=eps32, s=s, p=p, iterations=it,
                converged=converged, phi_ext21=phi_ext21, phi_ext32=phi_ext32, e_a21=e_a21,
                e_ext21=e_ext21, gci_fine21=safety * e_a21 / (rp21 - 1),
                monotone=0 < eps21 / eps32 < 1)


def self_test(verbose=True):
    """Returns a list of failures (empty when the implementation is right)."""
    failures = []

    def want(what, got, expected, tol):
        ok = abs(got - expected) <= tol
        if verbose:
            print(f"  [{'ok' if ok else 'FAIL'}] {what}: {got:.10g} (want {expected:g} +- {tol:g})")
        if not ok:
            failures.append(f"{what}: {got} != {expected}")

    # Celik et al. 2008, Table 1, first column (a 2D case, h = (A / N)^(1/2)):
    # N = 18000, 8000, 4500 -> r21 = 1.5, r32 = 4/3; phi = 6.063, 5.972, 5.863;
    # printed p = 1.53, phi_ext21 = 6.1685, e_a21 = 1.5%, e_ext21 = 1.7%,
    # GCI_fine21 = 2.2% (checked to the printed digits).
    h = [representative_size(1.0, n, dim=2) for n in (18000, 8000, 4500)]
    g = gci(h, [6.063, 5.972, 5.863])
    if verbose:
        print("Celik et al. 2008, Table 1, column 1:")
    want("r21", g["r21"], 1.5, 1e-12)
    want("r32", g["r32"], 4 / 3, 1e-12)
    want("p", g["p"], 1.53, 0.005)
    want("phi_ext21", g["phi_ext21"], 6.1685, 0.00005)
    want("e_a21 (%)", 100 * g["e_a21"], 1.5, 0.05)
    want("e_ext21 (%)", 100 * g["e_ext21"], 1.7, 0.05)
    want("GCI_fine21 (%)", 100 * g["gci_fine21"], 2.2, 0.05)

    # Manufactured: phi(h) = phi0 + C h^2, on unequal ratios (r21 != r32,
    # so q(p) matters), both signs of C.
    for c in (3.7, -0.8):
        phi0 = 1.234567
        h = [0.02, 0.02 * 1.41, 0.02 * 1.41 * 1.37]
        g = gci(h, [phi0 + c * x ** 2 for x in h])
        if verbose:
            print(f"manufactured phi = {phi0} + {c} h^2, r21 {g['r21']:.3f}, r32 {g['r32']:.3f} "
                  f"({g['iterations']} iterations):")
        want("p", g["p"], 2.0, 1e-6)
        want("phi_ext21", g["phi_ext21"], phi0, 1e-6)
        want("monotone", float(g["monotone"] and g["converged"]), 1.0, 0)
    # Oscillatory convergence: s = -1, not monotone.
    g = gci([1.0, 1.5, 2.25], [1.0, 1.1, 0.95])
    want("oscillatory: s", g["s"], -1.0, 0)
    want("oscillatory: not monotone", float(g["monotone"]), 0.0, 0)
    return failures


if __name__ == "__main__":
    if "--self-test" in sys.argv[1:]:
        bad = self_test()
        print("gci self-test: " + ("passed" if not bad else f"{len(bad)} FAILED"))
        sys.exit(1 if bad else 0)
    print(__doc__)
    sys.exit(2)
