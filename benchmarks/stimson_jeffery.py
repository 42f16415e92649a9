#!/usr/bin/python3
"""Two equal spheres translating along their line of centres in Stokes flow, against
Stimson & Jeffery's exact drag (doc/references/README.md, doc/particles.md), from l/d = 1.1
(a gap of 0.2 radii) to 3.

Each sphere (a = 1) moves at prescribed U = 1 along y; the drag factor of one is
lambda = F / (6 pi mu a U). The box is closed, so its walls raise the drag: every box size
is run with one sphere alone as well. To first order in a/L (method of reflections) the
walls reflect each sphere's Stokeslet back at both spheres alike, so with beta = 1 - 1/lambda_1
from the single sphere, the pair's unbounded drag factor follows from
1/lambda = 1/lambda_2 + 2 beta. Two box sizes show how much of the correction is left.
Steady Stokes in one step as in tests/validation_wall_3d.prm (rho = 1e-6, Delta t = 0.01).

Regenerate (from the top of the repository, after scripts/build.sh; about 6 min):
    /usr/bin/python3 benchmarks/stimson_jeffery.py
Writes doc/stimson_jeffery.csv and prints the table of doc/particles.md.
Options: --executable PATH   --work DIR (default benchmarks/work/stimson_jeffery)
"""
import argparse
import csv
import math
import os
import subprocess
import time

TOP = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# Stimson & Jeffery (1926), doc/references/README.md: lambda at centre distance l/d as
# published, to check the series below against.
PUBLISHED = {1.5: 0.698, 2.0: 0.742, 3.0: 0.805}
DISTANCES = (1.1, 1.25, 1.5, 2.0, 3.0)
# Terms of the series: it converges like exp(-2 n alpha), alpha >= 0.44 for l/d >= 1.1.
SERIES_TERMS = 100


def exact_drag(distance_over_d):
    """Stimson & Jeffery's exact drag factor, in bispherical coordinates: cosh(alpha) is
    the centre distance over the diameter."""
    alpha = math.acosh(distance_over_d)
    total = 0.0
    for n in range(1, SERIES_TERMS + 1):
        numerator = 4 * math.sinh((n + 0.5) * alpha) ** 2 - (2 * n + 1) ** 2 * math.sinh(alpha) ** 2
        denominator = 2 * math.sinh((2 * n + 1) * alpha) + (2 * n + 1) * math.sinh(2 * alpha)
        total += n * (n + 1) / ((2 * n - 1) * (2 * n + 3)) * (1 - numerator / denominator)
    return 4 / 3 * math.sinh(alpha) * total
# Box half-widths in radii; base cells 8 radii wide and 4 refinement levels: d/h = 4 at the
# spheres for every box.
BOXES = (16, 32)
BASE_CELL = 8
LEVELS = 4

PRM = """set Dimension = 3
set Gravity = 0, 0, 0
subsection Geometry
  set Lower corner = -{L}, -{L}, -{L}
  set Upper corner = {L}, {L}, {L}
  set Subdivisions = {n}, {n}, {n}
end
subsection Fluid
  set Density    = 1e-6
  set Viscosity  = 1
  set Convection = false
end
subsection Particles
  set Particles = {particles}
end
subsection Quadrature
  set Cut cells = level set
end
subsection Refinement
  set Particle refinement levels = {levels}
end
subsection Time
  set Time step = 0.01
  set End time  = 0.01
  set Scheme    = BDF1
end
subsection Output
  set Directory = {out}
  set VTU interval = 0
end
"""


def run(exe, work, name, half_width, centres):
    """Run the scene; returns (drag factor of each sphere, DoFs, wall seconds)."""
    out = os.path.join(work, name)
    sphere = "0, {y}, 0 : 1 : 1 : prescribed : 0, -1, 0"
    prm = PRM.format(L=half_width, n=2 * half_width // BASE_CELL, levels=LEVELS, out=out,
                     particles=" ; ".join(sphere.format(y=y) for y in centres))
    path = os.path.join(work, name + ".prm")
    with open(path, "w") as f:
        f.write(prm)
    start = time.time()
    log = subprocess.run([exe, path], check=True, capture_output=True, text=True).stdout
    seconds = time.time() - start
    dofs = int(log.split(" finite-element DoFs")[0].split()[-1])
    with open(os.path.join(out, "particles.csv"), newline="") as f:
        last = {}
        for row in csv.DictReader(f):
            last[int(row["id"])] = float(row["fy"])
    return [last[k] / (6 * math.pi) for k in sorted(last)], dofs, seconds


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--executable", default=os.path.join(TOP, "build", "fdparticle"))
    parser.add_argument("--work", default=os.path.join(TOP, "benchmarks", "work", "stimson_jeffery"))
    args = parser.parse_args()
    os.makedirs(args.work, exist_ok=True)
    for ratio, value in PUBLISHED.items():
        assert abs(exact_drag(ratio) - value) < 1e-3, f"the series at l/d = {ratio}"
    rows = []
    for L in BOXES:
        (single,), dofs, seconds = run(args.executable, args.work, f"box{L}_single", L, [0.0])
        beta = 1 - 1 / single
        rows.append(dict(box_half_width=L, distance_over_d="single", drag_box=single,
                         drag_ratio="", drag_corrected="", reference=1.0, error_percent="",
                         dofs=dofs, seconds=round(seconds, 1)))
        for ratio in DISTANCES:
            reference = exact_drag(ratio)
            half = ratio  # centres at -l/2 and l/2 with l = ratio * 2a
            drags, dofs, seconds = run(args.executable, args.work, f"box{L}_l{ratio}", L, [-half, half])
            pair = sum(drags) / 2
            corrected = 1 / (1 / pair + 2 * beta)
            rows.append(dict(box_half_width=L, distance_over_d=ratio, drag_box=pair,
                             drag_ratio=pair / single, drag_corrected=corrected, reference=reference,
                             error_percent=100 * (corrected / reference - 1), dofs=dofs,
                             seconds=round(seconds, 1)))
            print(rows[-1], flush=True)
    with open(os.path.join(TOP, "doc", "stimson_jeffery.csv"), "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        writer.writeheader()
        for r in rows:
            writer.writerow({k: (f"{v:.4f}" if isinstance(v, float) else v) for k, v in r.items()})
    print("| box half-width / a | l/d | lambda in the box | lambda_2/lambda_1 | corrected | exact | error % | DoFs | s |")
    print("|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        cells = [r["box_half_width"], r["distance_over_d"], r["drag_box"], r["drag_ratio"],
                 r["drag_corrected"], r["reference"], r["error_percent"], r["dofs"], r["seconds"]]
        print("| " + " | ".join(f"{c:.3f}" if isinstance(c, float) else str(c) for c in cells) + " |")


if __name__ == "__main__":
    main()
