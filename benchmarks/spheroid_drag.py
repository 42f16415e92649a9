#!/usr/bin/python3
"""Stokes drag of prolate spheroids (doc/shapes.md, "Stokes drag of a spheroid").

A fixed spheroid, long semi-axis a = 0.1 and short ones b = a/r (axis ratio r = 1, 2, 4),
in the centre of the periodic unit cube of prm/validation/array3d.prm, its axis along the
body force f = (1, 0, 0) ("along"), across it ("across") or turned by 30 degrees from it
about z ("tilted": the flow gains a y-component, compared too); steady Stokes in one BDF1 step of dt = 100 (mu = 1),
level-set cut cells, 4^3 base cells refined around the particle to 2b/h = 6.4 and 12.8
(r = 4: 6.4, and 9.6 and 12.8 on 6^3 and 8^3 base cells, 1.1 M unknowns).
F = fx, the force the particle holds (doc/method.md §9: f L^3 less the step's
rho U L^3/dt), and U = mean_vx over the cell, as in doc/validation.md section 1.

The periodic images slow the flow: for any particle small against the period L,
U/F = 1/R - 2.837297/(6 pi mu L) + O(|P|/L^3) (Hasimoto 1959; for a sphere the series
1/K = 1 - 1.7601 c^(1/3) + c - ..., doc/references), so the isolated resistance is
R = F / (U + 2.837297 F/(6 pi mu L)); the neglected term is of the order of the volume
fraction (1e-3 for r = 2). R is compared with the analytic resistance of a prolate
spheroid (Oberbeck 1876; Chwang & Wu 1975, e = sqrt(1 - 1/r^2), l = ln((1+e)/(1-e))):
    along:  16 pi mu a e^3 / ((1 + e^2) l - 2 e)
    across: 32 pi mu a e^3 / (2 e + (3 e^2 - 1) l)
and 6 pi mu a for the sphere (r = 1, the control of the periodic correction); tilted, the
mobility M = n n^T / R_along + (I - n n^T) / R_across (n the axis) gives U = M F.

Writes doc/shapes_drag.csv (each row with when its run ended, the build that ran it and the
machine) and prints the table of doc/shapes.md. About 40 minutes on 2 ranks; the finest runs
take 11.3 GB a rank (nearly all of a 24 GB machine: run it alone).

Usage (regenerate):  /usr/bin/python3 benchmarks/spheroid_drag.py [--ranks 2]
    [--work DIR] [--executable PATH] [--reuse] [--cases 1-along-3-4,2-along-4-4,...]
"""
import argparse
import csv
import math
import os
import re
import socket
import subprocess
import sys
from importlib.machinery import SourceFileLoader

TOP = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(TOP, "tests"))
from testlib import run_provenance  # noqa: E402  (after the path it lives on)
HASIMOTO = 2.837297  # 1.7601 (4 pi / 3)^(1/3): the periodic Stokeslet's self-term
A = 0.1
# (axis ratio, direction, particle refinement levels, base cells per edge):
# 2b/h = 2 (A/r) base 2^levels.
CASES = [(1, "along", 3, 4), (1, "along", 4, 4),
         (2, "along", 4, 4), (2, "across", 4, 4), (2, "tilted", 4, 4),
         (2, "along", 5, 4), (2, "across", 5, 4), (2, "tilted", 5, 4),
         (4, "along", 5, 4), (4, "across", 5, 4),
         (4, "along", 5, 6), (4, "across", 5, 6),
         (4, "along", 5, 8), (4, "across", 5, 8)]
TILT = 30  # degrees about z, "tilted": the axis in the x-y plane

# The scene: prm/validation/array3d.prm (the periodic unit cube, f = (1, 0, 0), steady
# Stokes in one step) with the particle, its levels and the solver replaced.
SCENE = os.path.join(TOP, "prm", "validation", "array3d.prm")
STUDY = SourceFileLoader("fdparticle_study", os.path.join(TOP, "tools", "fdparticle-study")).load_module()


def resistance(ratio, direction):
    """The resistance F/U of the isolated spheroid moving along or across its axis, mu = 1."""
    if ratio == 1:
        return 6 * math.pi * A
    e = math.sqrt(1 - 1 / ratio**2)
    l = math.log((1 + e) / (1 - e))
    if direction == "along":
        return 16 * math.pi * A * e**3 / ((1 + e**2) * l - 2 * e)
    return 32 * math.pi * A * e**3 / (2 * e + (3 * e**2 - 1) * l)


def mobility(ratio, direction):
    """(M_xx, M_yx) of the isolated spheroid, U = M F: along, across, or tilted by TILT
    degrees (M = n n^T / R_along + (I - n n^T) / R_across, n the axis)."""
    along, across = 1 / resistance(ratio, "along"), 1 / resistance(ratio, "across")
    if direction != "tilted":
        return (along if direction == "along" else across), 0.0
    c, s = math.cos(math.radians(TILT)), math.sin(math.radians(TILT))
    return c * c * along + s * s * across, c * s * (along - across)


def shape(ratio, direction):
    b = A / ratio
    if ratio == 1:
        return f"{A}"
    axes = (b, A, b) if direction == "across" else (A, b, b)
    turn = f", 0, 0, 1, {TILT}" if direction == "tilted" else ""
    return "ellipsoid " + ", ".join(f"{x:.6g}" for x in axes) + turn


def read_rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--executable", default=os.path.join(TOP, "build", "fdparticle"))
    p.add_argument("--work", default=os.path.join(TOP, "benchmarks", "work", "spheroid_drag"))
    p.add_argument("--ranks", type=int, default=2)
    p.add_argument("--reuse", action="store_true", help="keep finished runs")
    p.add_argument("--patch-memory", default="12",
                   help="Solver/Cut cell patch memory, GB a rank (the finest runs' patch "
                        "needs 7 GB on one rank; without it they take many more iterations)")
    p.add_argument("--cases", help="RATIO-DIRECTION-LEVELS-BASE,... (default: all)")
    args = p.parse_args()
    cases = CASES
    if args.cases:
        cases = [(int(r), d, int(l), int(n)) for r, d, l, n in (c.split("-") for c in args.cases.split(","))]
    os.makedirs(args.work, exist_ok=True)
    header = ["axis_ratio", "direction", "levels", "base_cells", "b_over_h", "dofs", "ranks", "wall_seconds",
              "peak_mb_per_rank", "fx", "mean_vx", "mean_vy", "resistance_periodic",
              "resistance_isolated", "analytic", "error_percent", "cross_error_percent_of_mxx",
              "date", "commit", "machine"]
    csv_path = os.path.join(TOP, "doc", "shapes_drag.csv")
    rows = []
    for ratio, direction, levels, base in cases:
        # The names of the 4^3 runs predate the base's own field.
        name = f"r{ratio}-{direction}-l{levels}" + (f"-n{base}" if base != 4 else "")
        out = os.path.join(args.work, name)
        prm = os.path.join(args.work, name + ".prm")
        timing = os.path.join(args.work, name + ".time")
        if not (args.reuse and os.path.exists(os.path.join(out, "particles.csv"))):
            with open(SCENE) as f:
                text = STUDY.apply_overrides(f.read(), {
                    "Particles/Particles": f"0.5, 0.5, 0.5 : {shape(ratio, direction)} : 1 : fixed",
                    "Refinement/Particle refinement levels": str(levels),
                    "Geometry/Subdivisions": f"{base}, {base}, {base}",
                    "Solver/Linear solver": "iterative",
                    "Solver/Cut cell patch memory": args.patch_memory,
                    "Output/Directory": out, "Output/VTU interval": "0"})
            with open(prm, "w") as f:
                f.write(text)
            command = [args.executable, prm]
            if args.ranks > 1:
                command = ["bash", os.path.join(TOP, "scripts", "mpirun.sh"), str(args.ranks)] + command
            print(f"{name}: running", flush=True)
            with open(os.path.join(args.work, name + ".log"), "w") as log:
                status = subprocess.call(["/usr/bin/time", "-f", "%e %M", "-o", timing] + command,
                                         stdout=log, stderr=subprocess.STDOUT)
            if status != 0:
                print(f"{name}: the run failed (see {name}.log)", file=sys.stderr)
                continue
        particle = read_rows(os.path.join(out, "particles.csv"))[-1]
        stats = read_rows(os.path.join(out, "statistics.csv"))[-1]
        with open(timing) as f:
            seconds, peak_kb = f.read().split()[-2:]
        with open(os.path.join(args.work, name + ".log")) as log:
            ranks = re.search(r"(\d+) MPI rank", log.read()).group(1)
        fx, u, v = (float(particle["fx"]), float(stats["mean_vx"]), float(stats["mean_vy"]))
        # The isolated mobility: U/F plus the images' isotropic self-term (mu = L = 1).
        m_xx, m_yx = u / fx + HASIMOTO / (6 * math.pi), v / fx
        reference_xx, reference_yx = mobility(ratio, direction)
        # M_yx against M_xx: the neglected image terms are a fraction of M_xx, not of M_yx.
        cross = f"{100 * (m_yx - reference_yx) / reference_xx:+.2f}" if reference_yx else ""
        rows.append([ratio, direction, levels, base, f"{(A / ratio) * base * 2**levels:.2f}",
                     stats["dofs"], ranks, seconds, f"{int(peak_kb) / 1024:.0f}",
                     f"{fx:.6f}", f"{u:.6g}", f"{v:.6g}", f"{fx / u:.5f}", f"{1 / m_xx:.5f}",
                     f"{1 / reference_xx:.5f}", f"{100 * (reference_xx / m_xx - 1):+.2f}",
                     cross, *run_provenance(out), socket.gethostname()])
        print(" ".join(str(x) for x in rows[-1][:17]), flush=True)
    with open(csv_path, "w", newline="") as f:
        csv.writer(f).writerows([header] + rows)
    print("\n| r = a/b | motion | 2b/h | unknowns | F/(μU) periodic | isolated | "
          "Oberbeck / Chwang & Wu | error % | M_yx error, % of M_xx | "
          "ranks | s | MB a rank |\n|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r[0]} | {r[1]} | {2 * float(r[4]):.1f} | {r[5]} | {r[12]} | {r[13]} | "
              f"{r[14]} | {r[15]} | {r[16]} | {r[6]} | {float(r[7]):.0f} | {r[8]} |")


if __name__ == "__main__":
    main()
