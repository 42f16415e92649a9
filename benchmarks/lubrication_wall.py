#!/usr/bin/python3
"""The lubrication correction on Brenner's sphere approaching a wall (doc/particles.md,
'Lubrication'). Runs prm/validation/wall.prm (a = 1, U = 1, mu = 1, steady Stokes in one
step) with Lubrication/Enabled = true at gaps delta/a = 0.1 ... 1 and particle refinement
levels 3 and 4 (d/h = 4, 8), with a time step of 0.001 so that the sphere moves 0.1 % of
its radius during the step. Each run reports the resolved force (particles.csv fy) and
the correction (contact_fy) separately, so one run gives kappa = F / (6 pi mu a U) with and
without the correction. The reference is Brenner's exact series (J. Fluid Mech. 1961),
summed here. Writes doc/lubrication_wall.csv and doc/lubrication_wall.png.

Regenerate (from the top of the repository, after scripts/build.sh; ~10 min on 2 cores):
    /usr/bin/python3 benchmarks/lubrication_wall.py [--executable PATH] [--work DIR]
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
GAPS = (0.1, 0.15, 0.25, 0.4, 0.6, 1.0)
LEVELS = (3, 4)


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


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--executable", default=os.path.join(TOP, "build", "fdparticle"))
    p.add_argument("--work", default=os.path.join(TOP, "benchmarks", "work", "lubrication_wall"))
    args = p.parse_args()
    os.makedirs(args.work, exist_ok=True)
    with open(os.path.join(TOP, "prm", "validation", "wall.prm")) as f:
        base = f.read()
    rows = []
    for levels in LEVELS:
        h = 16 / 4 / 2 ** levels
        for delta in GAPS:
            name = f"lv{levels}_gap{delta}"
            out = os.path.join(args.work, name)
            prm = os.path.join(args.work, name + ".prm")
            with open(prm, "w") as f:
                f.write(STUDY.apply_overrides(base, {
                    "Particles/Particles": f"0, {1 + delta}, 0 : 1 : 1 : prescribed : 0, -1, 0",
                    "Refinement/Particle refinement levels": levels,
                    "Time/Time step": 0.001, "Time/End time": 0.001,
                    "Output/Directory": out}) + "subsection Lubrication\n  set Enabled = true\nend\n")
            with open(os.path.join(args.work, name + ".log"), "w") as log:
                subprocess.run([args.executable, prm], stdout=log, stderr=subprocess.STDOUT, check=True)
            with open(os.path.join(out, "particles.csv")) as f:
                last = list(csv.DictReader(f))[-1]
            resolved = abs(float(last["fy"])) / (6 * math.pi)
            correction = abs(float(last["contact_fy"])) / (6 * math.pi)
            ref = brenner(delta)
            rows.append([f"{2 / h:g}", delta, f"{delta / h:.2g}", f"{ref:.4f}", f"{resolved:.4f}",
                         f"{100 * (resolved / ref - 1):+.1f}", f"{correction:.4f}",
                         f"{100 * ((resolved + correction) / ref - 1):+.1f}"])
            print(" ".join(str(c) for c in rows[-1]), flush=True)
    header = ["d/h", "delta/a", "gap/h", "Brenner kappa", "resolved", "error %",
              "correction", "error with correction %"]
    with open(os.path.join(DOC, "lubrication_wall.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        w.writerows(rows)
    data = os.path.join(args.work, "lubrication_wall.dat")
    with open(data, "w") as f:
        for levels in LEVELS:
            dh = f"{2 / (16 / 4 / 2 ** levels):g}"
            f.write(f'"d/h = {dh}"\n')
            for r in rows:
                if r[0] == dh:
                    f.write(f"{r[1]} {r[5]} {r[7]}\n")
            f.write("\n\n")
    subprocess.run(["gnuplot"], check=False, text=True, input=f"""
set terminal pngcairo size 800,550; set output '{DOC}/lubrication_wall.png'
set logscale x; set grid; set key right bottom
set title "Sphere approaching a wall: error of kappa against Brenner (1961)"
set xlabel 'gap delta/a'; set ylabel 'error (%)'
plot '{data}' index 0 using 1:2 with linespoints lc 1 dt 2 title 'd/h = 4, resolved', \\
     '{data}' index 0 using 1:3 with linespoints lc 1 title 'd/h = 4, with lubrication', \\
     '{data}' index 1 using 1:2 with linespoints lc 2 dt 2 title 'd/h = 8, resolved', \\
     '{data}' index 1 using 1:3 with linespoints lc 2 title 'd/h = 8, with lubrication', \\
     0 with lines lc rgb 'gray' notitle
""")


if __name__ == "__main__":
    main()
