"""Checks against published numbers (doc/validation.md; references and their
definitions in doc/references/README.md). The radius, viscosity, body force and
prescribed velocity are read from the run's own parameters.prm.

Usage: validation.py OUTPUT_DIR MODE REF TOL
  array      fixed particle in a periodic unit cell, driven by the body force f: at steady
             state the particle holds the whole cell, F = |f| |cell| (checked against the
             reported force to 0.1 %), and with U = mean_vx (statistics.csv, the superficial
             velocity): 2D  F / (mu U) = REF (Sangani & Acrivos 1982),
                        3D  K = F / (6 pi mu a U) = REF (Zick & Homsy 1982); within TOL.
  wall       sphere moving at prescribed speed U toward a wall (Stokes): the drag
             correction kappa = F / (6 pi mu a U) = REF (Brenner 1961); within TOL. F is
             the resolved force plus the contact force (the lubrication correction).
  pair       two spheres approaching each other at prescribed speeds +-U: the same for the
             last one, lambda = F / (6 pi mu a U) = REF (by symmetry Brenner's sphere
             approaching a free surface at half the gap); within TOL.
"""
import math
import sys
from testlib import table, check, finish, parameters

out, mode, ref, tol = sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4])
prm = parameters(out)
dim = int(prm["Dimension"])
mu = float(prm["Fluid/Viscosity"])
entry = [f.strip() for f in prm["Particles/Particles"].split(":")]
radius = float(entry[1])
last = table(out, "particles.csv")[-1]
stats = table(out, "statistics.csv")[-1]
check(all(math.isfinite(v) for v in list(last.values()) + list(stats.values())),
      "every number of the last rows is finite")

if mode == "array":
    lower = [float(x) for x in prm["Geometry/Lower corner"].split(",")]
    upper = [float(x) for x in prm["Geometry/Upper corner"].split(",")]
    f = float(prm["Fluid/Body force"].split(",")[0])
    cell = math.prod(u - l for u, l in zip(upper, lower))
    force = f * cell
    check(abs(last["fx"] / force - 1) < 1e-3,
          f"reported force fx = {last['fx']:.6f} = f |cell| = {force:.6f} (steady balance, 0.1 %)")
    U = stats["mean_vx"]
    value = force / (mu * U) if dim == 2 else force / (6 * math.pi * mu * radius * U)
    name = "F/(mu U)" if dim == 2 else "K = F/(6 pi mu a U)"
elif mode in ("wall", "pair"):
    U = abs(float(entry[4].split(",")[1]))
    value = abs(last["fy"] + last["contact_fy"]) / (6 * math.pi * mu * radius * U)
    name = "kappa = F/(6 pi mu a U)" if mode == "wall" else "lambda = F/(6 pi mu a U)"
else:
    sys.exit(f"unknown mode {mode}")
check(abs(value / ref - 1) < tol,
      f"{name} = {value:.5f} vs {ref} ({100 * (value / ref - 1):+.2f} %, tolerance {100 * tol:g} %)")
finish()
