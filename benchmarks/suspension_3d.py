#!/usr/bin/env python3
"""Table of benchmarks/suspension_3d.sh: one CSV row per finished run in WORK, and a
summary per solid fraction and mesh on standard output.

U/U0 is the settling velocity of the frozen configuration in the frame of zero volume
flux, −(mean particle v_z − mean v_z of the box), over Stokes' U0 = 2 Δρ g a²/(9 μ). A run
with one sphere has the exact value of a simple cubic array at its solid fraction c
(Sangani & Acrivos 1982, doc/references/README.md):
    U/U0 = 1/K = 1 − 1.7601 c^{1/3} + c − 1.5593 c² + 3.9799 c^{8/3} − 3.0734 c^{10/3};
measured over exact, averaged over its places, is the discretization's factor of that box
and mesh, and the suspension's U/U0 divided by it is the "corrected" column.

Usage: suspension_3d.py WORK CSV
"""
import csv
import math
import os
import re
import sys
from collections import defaultdict

work, out = sys.argv[1:3]
radius, viscosity, density_difference, gravity = 0.5, 1e4, 1.0, 1.0
u0 = 2 * density_difference * gravity * radius**2 / (9 * viscosity)


def sangani_acrivos(c):
    return (1 - 1.7601 * c ** (1 / 3) + c - 1.5593 * c**2 + 3.9799 * c ** (8 / 3)
            - 3.0734 * c ** (10 / 3))


def richardson_zaki(phi):
    return (1 - phi) ** 4.65


runs = []
for name in sorted(os.listdir(work)):
    m = re.fullmatch(r"n(\d+)_L([\d.]+)_c(\d+)_s(\d+)(?:_g[\d.]+)?", name)
    # Finished runs only: a step in statistics.csv and the peak memory written.
    if (not m or not os.path.exists(f"{work}/{name}/statistics.csv")
            or not os.path.exists(f"{work}/{name}.mem")):
        continue
    memory = open(f"{work}/{name}.mem").read().split()
    rows = list(csv.DictReader(open(f"{work}/{name}/statistics.csv")))
    if not memory or not rows:
        continue
    n, box, cells, seed = int(m[1]), float(m[2]), int(m[3]), int(m[4])
    # The placement's minimum gap, as the run was given it (suspension_scene.sh).
    gap = float(re.search(r"set Minimum gap\s*=\s*(\S+)", open(f"{work}/{name}.prm").read())[1])
    row = rows[-1]
    phi = n * 4 / 3 * math.pi * radius**3 / box**3
    slip = float(row["mean_particle_vz"]) - float(row["mean_vz"])
    runs.append({
        "particles": n, "box": box, "cells": cells, "solid_fraction": phi,
        "cells_per_diameter": 2 * radius * cells / box, "seed": seed,
        "unknowns": int(row["dofs"]), "linear_iterations": int(row["linear_iterations"]),
        "u_over_u0": -slip / u0, "ranks": int(open(f"{work}/{name}.ranks").read()),
        "seconds": float(row["wall_seconds"]),
        "peak_MB": int(memory[-1]) / 1024, "minimum_gap": gap})

# The discretization factor of each box and mesh, from its one-sphere runs.
factors = defaultdict(list)
for r in runs:
    if r["particles"] == 1:
        factors[(r["box"], r["cells"])].append(r["u_over_u0"] / sangani_acrivos(r["solid_fraction"]))
factor = {k: sum(v) / len(v) for k, v in factors.items()}

columns = ["particles", "box", "cells", "solid_fraction", "cells_per_diameter", "seed",
           "unknowns", "linear_iterations", "u_over_u0", "u_over_u0_corrected",
           "reference", "ranks", "seconds", "peak_MB", "minimum_gap"]
with open(out, "w") as f:
    f.write(",".join(columns) + "\n")
    for r in runs:
        k = (r["box"], r["cells"])
        r["u_over_u0_corrected"] = r["u_over_u0"] / factor[k] if k in factor else float("nan")
        # One sphere: the exact array value; a suspension: Richardson–Zaki, n = 4.65.
        phi = r["solid_fraction"]
        r["reference"] = sangani_acrivos(phi) if r["particles"] == 1 else richardson_zaki(phi)
        f.write(",".join(f"{r[c]:.6g}" if isinstance(r[c], float) else str(r[c])
                         for c in columns) + "\n")

print("N   phi     d/h  gap   runs  U/U0 (min..max)           corrected          RZ 4.65  "
      "Batchelor  factor  ranks  s/step  peak MB")
groups = defaultdict(list)
for r in runs:
    groups[(r["particles"], r["box"], r["cells"], r["minimum_gap"])].append(r)
for (n, box, cells, gap), rs in sorted(groups.items()):
    phi = rs[0]["solid_fraction"]
    u = [r["u_over_u0"] for r in rs]
    c = [r["u_over_u0_corrected"] for r in rs]
    print(f"{n:<4}{phi:<8.4f}{rs[0]['cells_per_diameter']:<5g}{gap:<6g}{len(rs):<6}"
          f"{sum(u) / len(u):.4f} ({min(u):.4f}..{max(u):.4f})  "
          f"{sum(c) / len(c):.4f} ({min(c):.4f}..{max(c):.4f})  "
          f"{richardson_zaki(phi):.4f}   {1 - 6.55 * phi:.4f}     "
          f"{factor.get((box, cells), float('nan')):.4f}  {rs[0]['ranks']:<6}"
          f"{sum(r['seconds'] for r in rs) / len(rs):<6.0f} {max(r['peak_MB'] for r in rs):.0f}")


# The box's size at a solid fraction of 0.10–0.105 and d/h = 2: the corrected U/U0 over
# Richardson–Zaki at each run's own φ (which takes out the small differences of φ between
# the boxes), per number of spheres, against the scatter between seeds.
by_n = defaultdict(list)
for r in runs:
    if (r["particles"] > 1 and 0.1 <= r["solid_fraction"] <= 0.105
            and abs(r["cells_per_diameter"] - 2) < 0.01 and r["minimum_gap"] == 0.25):
        by_n[r["particles"]].append(r["u_over_u0_corrected"] / richardson_zaki(r["solid_fraction"]))
for n, q in sorted(by_n.items()):
    print(f"phi 0.10-0.105, d/h = 2, N = {n}: corrected U/U0 over Richardson-Zaki "
          f"{sum(q) / len(q):.3f} ({min(q):.3f}..{max(q):.3f}, {len(q)} seeds)")
