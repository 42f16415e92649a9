#!/usr/bin/python3
"""The lubrication correction on Brenner's sphere approaching a wall (doc/particles.md,
'Lubrication'). Runs prm/validation/wall.prm (a = 1, U = 1, mu = 1, steady Stokes in one
step) with Lubrication/Enabled = true at gaps delta/a = 0.03 ... 1 and particle
refinement levels 3 and 4 (d/h = 4, 8; --levels 3 4 5 adds d/h = 16: 455 k DoFs and about
14 GB per run with the direct solver). The time step is 1e-5, so that the sphere moves
0.001 % of its radius during the step (the resolved force sees the gap at the start of the
step, the correction at its end), and the density 1e-9 keeps alpha = 1e-4 as in the prm.
Each run reports the resolved force (particles.csv fy) and the correction (contact_fy)
separately, so one run gives kappa = F / (6 pi mu a U) with and without the correction,
and the shift s: the gap widening delta + s at which Brenner's kappa equals the resolved
one (the 'auto' Gap shift is fitted to it). The reference is Brenner's exact series
(J. Fluid Mech. 1961), summed here. Writes doc/lubrication_wall.csv and
doc/lubrication_wall.png.

--dimension 2 runs the same scene with a cylinder (per unit length; kappa = F/(mu U)). No
exact solution exists in 2D, so the reference is the resolved force of the same scene on
two fine meshes, --reference-dh (default d/h = 512 and 1024: 13 and 26 cells in the
thinnest gap, 0.05a), extrapolated to h -> 0 at first order (extrapolated_reference), and
the shift s solves resolved = reference - (C(delta) - C(delta + s)) for the leading term
C(g) = 3 sqrt(2) pi (a/g)^(3/2). Writes doc/lubrication_wall_2d.csv and .png.

Regenerate (from the top of the repository, after scripts/build.sh; about 12 min for 3D
levels 3 4, 45 min with 5, 10 min for 2D):
    /usr/bin/python3 benchmarks/lubrication_wall.py [--executable PATH] [--work DIR]
        [--levels 3 4] [--dimension 2 [--reference-dh 512 1024]]
"""
import argparse
import csv
import math
import os
import subprocess
from importlib.machinery import SourceFileLoader

TOP = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
STUDY = SourceFileLoader("fdparticle_study", os.path.join(TOP, "tools", "fdparticle-study")).load_module()
DOC = os.path.join(TOP, "doc")
GAPS = {3: (0.03, 0.05, 0.1, 0.15, 0.25, 0.4, 0.6, 1.0), 2: (0.05, 0.1, 0.15, 0.25, 0.4, 0.6, 1.0)}


def cell_size(levels):
    """The finest cell edge: wall.prm's base cells of 4a halved per refinement level."""
    return 16 / 4 / 2 ** levels


def reference_mesh(d_over_h):
    """(base subdivisions per direction, particle refinement levels) of the 16a box for
    d/h = 2a/h, a power of two: wall.prm's 4 base cells, and more where the levels would
    pass 8, the most Refinement/Particle refinement levels accepts."""
    subdivisions, levels = 4, round(math.log2(2 * d_over_h))
    assert 2 ** levels == 2 * d_over_h, "d/h of a reference must be a power of two"
    while levels > 8:
        subdivisions, levels = 2 * subdivisions, levels - 1
    return subdivisions, levels


def extrapolated_reference(run_force, gaps, d_over_h):
    """2D reference {gap: force}: the resolved force on the meshes d_over_h = (coarse,
    fine), fine = 2 coarse, extrapolated to h -> 0 at first order, fine + (fine - coarse).
    The resolved force of a thin gap converges slowly: from d/h = 128 to 1024 it grows by
    24-32 % at 0.05a, and from 512 to 1024 its increments are 0.5-0.7 of those from 256
    to 512 (doc/particles.md, Lubrication). run_force(subdivisions, levels, gap) -> resolved force."""
    coarse, fine = d_over_h
    assert fine == 2 * coarse, "the reference meshes must be d/h and 2 d/h"
    references = {}
    for gap in gaps:
        f_coarse, f_fine = (run_force(*reference_mesh(dh), gap) for dh in (coarse, fine))
        references[gap] = 2 * f_fine - f_coarse
        print(f"reference at gap {gap}: {f_coarse:.4f} (d/h = {coarse}), {f_fine:.4f} "
              f"(d/h = {fine}), extrapolated {references[gap]:.4f}", flush=True)
    return references


def brenner(delta):
    """kappa of a sphere moving normal to a plane wall at gap delta/a (Brenner 1961)."""
    alpha = math.acosh(1 + delta)
    total = 0.0
    for n in range(1, 100000):
        if (2 * n + 1) * alpha > 600:  # the terms have converged long before sinh overflows
            break
        num = 2 * math.sinh((2 * n + 1) * alpha) + (2 * n + 1) * math.sinh(2 * alpha)
        den = 4 * math.sinh((n + 0.5) * alpha) ** 2 - (2 * n + 1) ** 2 * math.sinh(alpha) ** 2
        total += n * (n + 1) / ((2 * n - 1) * (2 * n + 3)) * (num / den - 1)
    return 4.0 / 3.0 * math.sinh(alpha) * total


def effective_gap(kappa, law=brenner):
    """The gap at which law (default Brenner's wall kappa, any drag that falls as the gap
    grows) equals kappa."""
    low, high = 1e-6, 100.0
    for _ in range(200):
        middle = math.sqrt(low * high)
        low, high = (middle, high) if law(middle) > kappa else (low, middle)
    return math.sqrt(low * high)


def run_scene(args, base, name, levels, balls, subdivisions=4):
    """Resolved force and correction, per (6 pi) in 3D, on the last of the prescribed
    balls (a = 1, moving along y) given as (centre y, velocity y), with lubrication on:
    3D in wall.prm's box, 2D in (-8, 0)-(8, 16) on subdivisions^2 base cells. The wall
    benchmark and benchmarks/lubrication_pair.py run their scenes through it."""
    out = os.path.join(args.work, name)
    prm = os.path.join(args.work, name + ".prm")
    zero = ", 0" if args.dimension == 3 else ""
    # The density keeps alpha = rho/dt at the prm's 1e-4 << mu/a^2: the flow reaches the
    # walls of the box within the step, as a steady one does.
    scene = {"Refinement/Particle refinement levels": levels, "Fluid/Density": 1e-9,
             "Time/Time step": 1e-5, "Time/End time": 1e-5, "Output/Directory": out,
             "Particles/Particles": "; ".join(f"0, {y}{zero} : 1 : 1 : prescribed : 0, {v}{zero}"
                                              for y, v in balls)}
    if args.dimension == 2:
        scene.update({"Dimension": 2, "Gravity": "0, 0", "Geometry/Lower corner": "-8, 0",
                      "Geometry/Upper corner": "8, 16",
                      "Geometry/Subdivisions": f"{subdivisions}, {subdivisions}"})
    with open(prm, "w") as f:
        f.write(STUDY.apply_overrides(base, scene) + "subsection Lubrication\n  set Enabled = true\nend\n")
    with open(os.path.join(args.work, name + ".log"), "w") as log:
        subprocess.run([args.executable, prm], stdout=log, stderr=subprocess.STDOUT, check=True)
    with open(os.path.join(out, "particles.csv")) as f:
        last = [r for r in csv.DictReader(f) if r["id"] == str(len(balls) - 1)][-1]
    scale = 6 * math.pi if args.dimension == 3 else 1.0
    return float(last["fy"]) / scale, float(last["contact_fy"]) / scale


def run(args, base, levels, delta, subdivisions=4):
    """Resolved force and correction, in units of kappa, of the sphere (cylinder) at gap
    delta with the given particle refinement levels (2D: on subdivisions^2 base cells)."""
    return run_scene(args, base, f"{args.dimension}d_{subdivisions}_lv{levels}_gap{delta}",
                     levels, [(1 + delta, -1)], subdivisions)


def cylinder_shift(delta, resolved, reference):
    """s with resolved = reference - (C(delta) - C(delta + s)), C the 2D leading term."""
    C = lambda g: 3 * math.sqrt(2) * math.pi * g ** -1.5
    wide = C(delta) - reference + resolved
    return (3 * math.sqrt(2) * math.pi / wide) ** (2 / 3) - delta if wide > 0 else float("nan")


def arguments(description, name, levels):
    """The command line of this benchmark and of benchmarks/lubrication_pair.py (work
    directory benchmarks/work/NAME, default particle refinement LEVELS), and the base scene
    prm/validation/wall.prm."""
    p = argparse.ArgumentParser(description=description, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--executable", default=os.path.join(TOP, "build", "fdparticle"))
    p.add_argument("--work", default=os.path.join(TOP, "benchmarks", "work", name))
    p.add_argument("--levels", type=int, nargs="+", default=levels,
                   help="particle refinement levels (d/h = 2^(levels - 1))")
    p.add_argument("--dimension", type=int, choices=(2, 3), default=3)
    p.add_argument("--reference-dh", type=int, nargs=2, default=[512, 1024],
                   help="2D: the two meshes (d/h) of the extrapolated reference")
    args = p.parse_args()
    os.makedirs(args.work, exist_ok=True)
    with open(os.path.join(TOP, "prm", "validation", "wall.prm")) as f:
        return args, f.read()


def main():
    args, base = arguments(__doc__, "lubrication_wall", [3, 4])
    if args.dimension == 2:
        references = extrapolated_reference(
            lambda subdivisions, levels, delta: run(args, base, levels, delta, subdivisions)[0],
            GAPS[2], args.reference_dh)
    rows = []
    for levels in args.levels:
        h = cell_size(levels)
        for delta in GAPS[args.dimension]:
            resolved, correction = run(args, base, levels, delta)
            if args.dimension == 3:
                ref, shift = brenner(delta), effective_gap(resolved) - delta
            else:
                ref = references[delta]
                shift = cylinder_shift(delta, resolved, ref)
            rows.append(table_row(h, delta, ref, resolved, shift, correction))
    reference_dh = "{} and {}, extrapolated".format(*args.reference_dh)
    reference = "Brenner kappa" if args.dimension == 3 else f"reference (d/h = {reference_dh})"
    header = ["d/h", "delta/a", "gap/h", reference, "resolved", "error %", "shift s/a",
              "correction", "error with correction %"]
    stem = os.path.join(DOC, "lubrication_wall" + ("" if args.dimension == 3 else "_2d"))
    title = ("Sphere approaching a wall: error of kappa against Brenner (1961)" if args.dimension == 3
             else f"Cylinder approaching a wall: error against d/h = {reference_dh}")
    write_results(stem, header, rows, args.levels, os.path.join(args.work, f"lubrication_wall_{args.dimension}d.dat"),
                  title, "gap delta/a")


def table_row(h, gap, reference, resolved, shift, correction):
    """One row of the table (and of the progress printed): d/h, the gap in radii and in
    cells, the reference, the resolved force, its error, the shift, the correction and the
    error with it. Shared with benchmarks/lubrication_pair.py."""
    row = [f"{2 / h:g}", gap, f"{gap / h:.2g}", f"{reference:.4f}", f"{resolved:.4f}",
           f"{100 * (resolved / reference - 1):+.1f}", f"{shift:.3f}",
           f"{correction:.4f}", f"{100 * ((resolved + correction) / reference - 1):+.1f}"]
    print(" ".join(str(c) for c in row), flush=True)
    return row


def write_results(stem, header, rows, levels, data, title, xlabel):
    """STEM.csv, and STEM.png: the error with and without the correction against the gap,
    one pair of curves per mesh (through the gnuplot data file DATA)."""
    with open(stem + ".csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        w.writerows(rows)
    with open(data, "w") as f:
        for level in levels:
            dh = f"{2 / cell_size(level):g}"
            f.write(f'"d/h = {dh}"\n')
            for r in rows:
                if r[0] == dh:
                    f.write(f"{r[1]} {r[5]} {r[8]}\n")
            f.write("\n\n")
    curves = ", \\\n     ".join(
        f"'{data}' index {i} using 1:2 with linespoints lc {i + 1} dt 2 title 'd/h = {2 / cell_size(l):g}, resolved', "
        f"'{data}' index {i} using 1:3 with linespoints lc {i + 1} title 'd/h = {2 / cell_size(l):g}, with lubrication'"
        for i, l in enumerate(levels))
    subprocess.run(["gnuplot"], check=False, text=True, input=f"""
set terminal pngcairo size 800,550; set output '{stem}.png'
set logscale x; set grid; set key right bottom
set title "{title}"
set xlabel '{xlabel}'; set ylabel 'error (%)'
plot {curves}, \\
     0 with lines lc rgb 'gray' notitle
""")


if __name__ == "__main__":
    main()
