#!/usr/bin/python3
"""fdparticle against published numbers. Runs the scenes of prm/validation/ at
increasing resolution and writes doc/validation.md (tables: reference, ours per resolution,
relative error, d/h, DoFs, wall time), doc/validation/*.csv and doc/validation/*.png.
References, their citations and definitions: doc/references/README.md.

Regenerate (from the top of the repository, after scripts/build.sh):
    /usr/bin/python3 benchmarks/validation/run.py                  # ~25 min on 2 cores
    /usr/bin/python3 benchmarks/validation/run.py --tencate E1,E2,E3,E4
                    # + ten Cate at d/h = 3 and 6 (~10–20 and 40–60 min a case)
        --tencate-meshes 5x8x5/2,5x8x5/3,7x11x7/3   # + d/h = 8.25 (~1.5–2.5 h a case)
Options: --only array2d,array3d,shear,wall,closure,tencate   --reuse (keep finished runs)
         --no-new-runs (tables from the finished runs only, e.g. after runs in parallel)
         --work DIR (default benchmarks/work/validation)       --executable PATH
"""
import argparse
import csv
import math
import os
import subprocess
import sys
import time
from importlib.machinery import SourceFileLoader

TOP = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
STUDY = SourceFileLoader("fdparticle_study", os.path.join(TOP, "tools", "fdparticle-study")).load_module()
DOC = os.path.join(TOP, "doc")
REFS = os.path.join(DOC, "references")  # published reference data (doc/references/README.md)


def read_rows(path):
    with open(path, newline="") as f:
        return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]


class Runner:
    def __init__(self, args):
        self.exe, self.work = args.executable, args.work
        self.reuse, self.no_new_runs = args.reuse or args.no_new_runs, args.no_new_runs
        os.makedirs(self.work, exist_ok=True)
        self.started = time.time()

    def run(self, name, base, overrides):
        """Run prm/validation/BASE with the overrides as WORK/NAME; returns
        (particles rows, statistics rows, dofs of the last step, wall seconds)."""
        out = os.path.join(self.work, name)
        done = os.path.join(out, "statistics.csv")
        finished = os.path.exists(os.path.join(out, "smoothness.csv"))
        if not finished and self.no_new_runs:
            print(f"    {name}: not run (--no-new-runs), left out", flush=True)
            return None
        if not (self.reuse and finished):
            with open(os.path.join(TOP, "prm", "validation", base)) as f:
                text = f.read()
            overrides = dict(overrides, **{"Output/Directory": out, "Output/VTU interval": "0"})
            prm = os.path.join(self.work, name + ".prm")
            with open(prm, "w") as f:
                f.write(STUDY.apply_overrides(text, overrides))
            elapsed = time.time() - self.started
            print(f"[{elapsed / 60:5.1f} min] {name}", flush=True)
            with open(os.path.join(self.work, name + ".log"), "w") as log:
                status = subprocess.call([self.exe, prm], stdout=log, stderr=subprocess.STDOUT)
            if status != 0:
                print(f"    {name}: exit {status} (see {name}.log)", flush=True)
        if not os.path.exists(done):
            return None
        stats = read_rows(done)
        if not stats:  # the run died before its first step (e.g. out of memory)
            return None
        parts = read_rows(os.path.join(out, "particles.csv"))
        return parts, stats, int(stats[-1]["dofs"]), sum(r["wall_seconds"] for r in stats)


def pct(value, ref):
    return 100 * (value / ref - 1)


def table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(str(c) for c in r) + " |" for r in rows]
    return "\n".join(lines)


def write_csv(name, header, rows):
    os.makedirs(os.path.join(DOC, "validation"), exist_ok=True)
    with open(os.path.join(DOC, "validation", name + ".csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        w.writerows(rows)


def gnuplot(script):
    subprocess.run(["gnuplot"], input=script, text=True, check=False)


def error_plot(name, title, xlabel, series):
    """series: list of (label, [(x, |error| %)]) -> doc/validation/NAME.png, log-log."""
    data = os.path.join(DOC, "validation", name + ".dat")
    with open(data, "w") as f:
        for label, points in series:
            f.write(f'"{label}"\n')
            for x, e in points:
                f.write(f"{x} {max(abs(e), 1e-3)}\n")
            f.write("\n\n")
    plots = ", ".join(f"'{data}' index {i} using 1:2 with linespoints title columnheader(1)"
                      for i in range(len(series)))
    gnuplot(f"""set terminal pngcairo size 800,550; set output '{DOC}/validation/{name}.png'
set logscale xy; set grid; set key left bottom; set title '{title}'
set xlabel '{xlabel}'; set ylabel '|relative error| (%)'
plot {plots}, 1 with lines dt 2 lc rgb 'gray' title '1 %'
""")


# ---- cases ------------------------------------------------------------------------------
def array_case(r, md, dim, levels):
    """Periodic unit cell with one fixed particle of solid fraction c, driven by a unit
    body force: F = f |cell| = 1 and U = mean_vx give F/(mu U) (2D) or K (3D)."""
    if dim == 2:
        refs, base_cells = {0.05: 15.56, 0.20: 51.53, 0.40: 217.89}, 16
        radius = lambda c: math.sqrt(c / math.pi)
        centre, quantity = "0.5, 0.5", "F/(mu U)"
    else:
        refs, base_cells = {0.027: 2.008, 0.064: 2.810, 0.125: 4.292}, 4
        radius = lambda c: (3 * c / (4 * math.pi)) ** (1 / 3)
        centre, quantity = "0.5, 0.5, 0.5", "K"
    rows, series = [], []
    for c, ref in refs.items():
        a = radius(c)
        points = []
        for lv in levels:
            res = r.run(f"array{dim}d_c{c}_lv{lv}", f"array{dim}d.prm", {
                "Particles/Particles": f"{centre} : {a:.6f} : 1 : fixed",
                "Refinement/Particle refinement levels": lv})
            if not res:
                continue
            parts, stats, dofs, wall = res
            drag_per_speed = parts[-1]["fx"] / stats[-1]["mean_vx"]
            value = drag_per_speed if dim == 2 else drag_per_speed / (6 * math.pi * a)
            dh = 2 * a * base_cells * 2 ** lv
            rows.append([c, ref, f"{value:.4f}", f"{pct(value, ref):+.2f}", f"{dh:.1f}", dofs, f"{wall:.1f}"])
            points.append((dh, pct(value, ref)))
        series.append((f"c = {c}", points))
    header = ["c", f"reference {quantity}", "ours", "error %", "d/h", "DoFs", "wall s"]
    write_csv(f"array{dim}d", header, rows)
    return header, rows, series


def array2d(r, md):
    header, rows, series = array_case(r, md, 2, range(0, 5))
    error_plot("array2d", "2D square array of cylinders (Sangani & Acrivos 1982)", "d/h", series)
    md.append("## 2. Square array of fixed cylinders, 2D (Sangani & Acrivos 1982)\n\n"
              "Periodic unit cell [0,1]², one fixed disk of radius a = √(c/π) in the centre, "
              "body force f = (1, 0), μ = 1, steady Stokes (one BDF1 step of Δt = 100). At steady "
              "state the disk holds the whole cell: F = f·L² (the reported f_x agrees to "
              "< 0.02 %), and U = mean_vx over the whole cell. 16² base cells + 0…4 particle "
              "refinement levels, level-set quadrature. `prm/validation/array2d.prm`.\n\n"
              + table(header, rows) + "\n\n![](validation/array2d.png)\n")


def array3d(r, md, levels):
    header, rows, series = array_case(r, md, 3, levels)
    error_plot("array3d", "3D simple cubic array of spheres (Zick & Homsy 1982)", "d/h", series)
    md.append("## 1. Simple cubic array of fixed spheres, 3D (Zick & Homsy 1982)\n\n"
              "Periodic unit cell [0,1]³, one fixed sphere, a = (3c/4π)^{1/3}, body force "
              "(1, 0, 0), μ = 1, steady Stokes in one step; K = F/(6πμaU) with F = f·L³ and "
              "U = mean_vx. 4³ base cells + particle refinement levels, level-set quadrature. "
              "`prm/validation/array3d.prm`.\n\n"
              + table(header, rows) + "\n\n![](validation/array3d.png)\n")


def shear(r, md):
    rows = []
    for dim, base, meshes in ((2, "shear2d.prm", ("32, 32", "64, 64", "128, 128")),
                              (3, "shear3d.prm", ("8, 8, 8", "16, 16, 16"))):
        for mesh in meshes:
            n = int(mesh.split(",")[0])
            for closure in ("torque balance", "kinematic"):
                tag = closure.split()[0]
                res = r.run(f"shear{dim}d_{n}_{tag}", base, {
                    "Geometry/Subdivisions": mesh,
                    "Particles/Angular velocity closure": closure,
                    "Quadrature/Cut cells": "level set"})
                if not res:
                    continue
                parts, stats, dofs, wall = res
                w = parts[-1]["wz"]
                rows.append([f"{dim}D", f"{0.2 * n:.1f}", closure, -0.5, f"{w:.5f}", f"{pct(w, -0.5):+.2f}",
                             dofs, f"{wall:.1f}"])
    header = ["dim", "d/h", "closure", "reference ω_z", "ours", "error %", "DoFs", "wall s"]
    write_csv("shear", header, rows)
    md.append("## 3. Free particle in simple shear, Stokes (ω = −γ̇/2)\n\n"
              "Walls y = ±0.5 slide with ±0.5 (γ̇ = 1), other directions periodic, "
              "2R/H = 0.2, neutrally buoyant particle at the centre, two BDF1 steps of Δt = 100. "
              "The torque-balance closure (doc/method.md (F5), our default) and the seed's "
              "kinematic closure |P|ω = ½∫_P ∇×u (seed 3.14d) side by side. "
              "`prm/validation/shear2d.prm`, `shear3d.prm`.\n\n" + table(header, rows) + "\n")


def wall(r, md):
    refs = {4: 1.2851, 1: 2.1255, 0.4: 3.73562, 0.1: 11.4592}
    rows, series = [], []
    for gap, ref in refs.items():
        points = []
        for box, lv in ((16, 3), (16, 4), (32, 5)):
            if box == 32 and gap < 1:
                continue
            half = box / 2
            res = r.run(f"wall_g{gap}_box{box}_lv{lv}", "wall.prm", {
                "Geometry/Lower corner": f"{-half}, 0, {-half}",
                "Geometry/Upper corner": f"{half}, {box}, {half}",
                "Particles/Particles": f"0, {1 + gap}, 0 : 1 : 1 : prescribed : 0, -1, 0",
                "Refinement/Particle refinement levels": lv})
            if not res:
                continue
            parts, stats, dofs, wall_s = res
            value = abs(parts[-1]["fy"]) / (6 * math.pi)
            h = box / 4 / 2 ** lv
            dh = 2 / h
            rows.append([gap, ref, f"{box}a", f"{dh:g}", f"{gap / h:.2g}", f"{value:.4f}",
                         f"{pct(value, ref):+.2f}", dofs, f"{wall_s:.1f}"])
            if box == 16:
                points.append((dh, pct(value, ref)))
        series.append((f"delta/a = {gap}", points))
    header = ["δ/a", "Brenner κ", "box", "d/h", "gap/h", "ours", "error %", "DoFs", "wall s"]
    write_csv("wall", header, rows)
    error_plot("wall", "Sphere moving toward a wall (Brenner 1961), box 16a", "d/h", series)
    md.append("## 4. Sphere moving toward a wall at prescribed speed (Brenner 1961)\n\n"
              "a = 1, U = 1 toward the floor y = 0, μ = 1, steady Stokes in one step (ρ = 1e-6, "
              "Δt = 0.01: the sphere moves 1 % of a). The box is 16a wide and 16a high (8a to the "
              "side walls) or twice that; 4³ base cells + particle refinement levels, level-set "
              "quadrature. `prm/validation/wall.prm`.\n\n" + table(header, rows) +
              "\n\n![](validation/wall.png)\n")


def closure(r, md):
    """The seed's sediment scene in 2D with the disk off the axis (x = 0.05, so that it
    turns), both closures; the 3D scene is symmetric and both give omega = 0 to rounding."""
    series = []
    for c in ("torque balance", "kinematic"):
        tag = c.split()[0]
        res = r.run(f"closure_{tag}", os.path.join("..", "sediment2d.prm"), {
            "Particles/Particles": "0.05, 1 : 0.2 : 1.5",
            "Particles/Angular velocity closure": c, "Quadrature/Cut cells": "level set",
            "Refinement/Particle refinement levels": 2, "Time/End time": 40})
        if res:
            series.append((c, res[0]))
    if len(series) == 2:
        out = os.path.join(DOC, "validation", "closure.dat")
        with open(out, "w") as f:
            for label, parts in series:
                f.write(f'"{label}"\n' + "".join(f"{p['time']} {p['wz']} {p['vy']}\n" for p in parts) + "\n\n")
        gnuplot(f"""set terminal pngcairo size 900,600; set output '{DOC}/validation/closure.png'
set datafile separator whitespace; set multiplot layout 2,1; set grid; set xlabel 't'
set ylabel 'omega_z'; set title 'Sediment scene (2D, disk at x = 0.05): angular velocity closures'
plot '{out}' index 0 using 1:2 with lines title columnheader(1), '{out}' index 1 using 1:2 with lines title columnheader(1)
set title ''; set ylabel 'V_y'
plot '{out}' index 0 using 1:3 with lines title columnheader(1), '{out}' index 1 using 1:3 with lines title columnheader(1)
unset multiplot
""")
        w = [max(abs(p["wz"]) for p in s[1]) for s in series]
        md.append("## 6. The seed's sediment scene with both angular-velocity closures\n\n"
                  "prm/sediment2d.prm with the disk started 0.05 off the axis (on the axis both "
                  "closures give ω = 0 by symmetry, as the 3D scene does), 8×16 + 2 particle "
                  "refinement levels, level set, to t = 40. Largest |ω_z|: torque balance "
                  f"{w[0]:.3e}, kinematic {w[1]:.3e}.\n\n![](validation/closure.png)\n")


TENCATE_BOX_MM = (100, 160, 100)  # prm/validation/tencate.prm
TENCATE_D_MM = 15


def tencate_mesh(mesh):
    """'5x8x5/3' -> (base '5x8x5', subdivisions, levels, d/h), h the largest edge of the
    finest cells."""
    base, levels = mesh.split("/")
    subdivisions = [int(n) for n in base.split("x")]
    h = max(length / n for length, n in zip(TENCATE_BOX_MM, subdivisions)) / 2 ** int(levels)
    return base, subdivisions, int(levels), TENCATE_D_MM / h


def tencate(r, md, cases, meshes):
    """Each case on each mesh (base subdivisions / particle refinement levels)."""
    fluids = {"E1": (970, 0.373, 0.03599), "E2": (965, 0.212, 0.05718),
              "E3": (962, 0.113, 0.08727), "E4": (960, 0.058, 0.12224)}
    rows, curves = [], []
    for case in cases:
        rho, mu, umax = fluids[case]
        for mesh in meshes:
            base, subdivisions, level, d_over_h = tencate_mesh(mesh)
            name = f"tencate_{case}_{mesh.replace('/', '_lv')}"
            res = r.run(name, "tencate.prm", {
                "Fluid/Density": rho, "Fluid/Viscosity": mu,
                "Geometry/Subdivisions": ", ".join(map(str, subdivisions)),
                "Refinement/Particle refinement levels": level,
                "Time/End time": 2.5 if case in ("E1", "E2") else 1.6})
            if not res:
                continue
            parts, stats, dofs, wall_s = res
            peak = max(-p["vy"] for p in parts)
            rows.append([case, umax, f"{peak:.5f}", f"{pct(peak, umax):+.2f}", f"{d_over_h:.3g}",
                         base, max(int(s["dofs"]) for s in stats),
                         f"{wall_s / 60:.1f}", len(stats)])
            curves.append((case, d_over_h, os.path.join(r.work, name, "particles.csv")))
    if not rows:
        return
    header = ["case", "u_max (Table II)", "ours", "error %", "d/h", "base cells", "DoFs (max)",
              "wall min", "steps"]
    write_csv("tencate", header, rows)
    plots = []
    colours = {case: i + 1 for i, case in enumerate(cases)}
    for case, d_over_h, path in curves:
        dash = 1 + sum(c[1] > d_over_h for c in curves if c[0] == case)  # finest solid
        plots.append(f"'{path}' using 1:(-$7) every ::1 with lines lw 2 dt {dash} lc {colours[case]} "
                     f"title '{case} d/h = {d_over_h:g}'")
    for case in cases:
        ref = os.path.join(REFS, "tencate2002", f"{case}_velocity.csv")
        plots.append(f"'{ref}' using 1:(-$2) with points pt 7 ps 0.6 lc {colours[case]} "
                     f"title '{case} experiment'")
    gnuplot(f"""set terminal pngcairo size 900,550; set output '{DOC}/validation/tencate.png'
set datafile separator ','; set grid; set xlabel 't (s)'; set ylabel 'settling speed (m/s)'
set title 'ten Cate et al. (2002): settling speed'; set key right top
plot {', '.join(plots)}
""")
    md.append("## 5. ten Cate et al. (2002): a sphere settling in a closed box\n\n"
              "Full 3D box 100×160×100 mm, d = 15 mm, ρ_p = 1120 kg/m³, released 127.5 mm above "
              "the floor; base cells (subdivisions of the box) + levels of particle-following "
              "refinement: "
              + ", ".join(f"{base.replace('x', '×')} + {level} (d/h = {d_over_h:.3g})"
                          for base, _, level, d_over_h in map(tencate_mesh, meshes))
              + "; d/h by the longest edge of the finest cells; level set, BDF2, "
              "Δt = 0.01 s, Navier–Stokes, lubrication on, the default solvers. "
              "`prm/validation/tencate.prm`. In the plot a case's finest mesh is the solid "
              "line, the next coarser dashed, the next dotted.\n\n"
              + table(header, rows) + "\n\n![](validation/tencate.png)\n")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--only", default="array2d,array3d,shear,wall,closure")
    p.add_argument("--tencate", default="", help="cases, e.g. E2,E4 (long)")
    p.add_argument("--tencate-meshes", default="5x8x5/2,5x8x5/3",
                   help="base subdivisions/particle refinement levels; the default: d/h = 3, 6")
    p.add_argument("--array3d-levels", default="1,2,3")
    p.add_argument("--work", default=os.path.join(TOP, "benchmarks", "work", "validation"))
    p.add_argument("--executable", default=os.path.join(TOP, "build", "fdparticle"))
    p.add_argument("--reuse", action="store_true")
    p.add_argument("--no-new-runs", action="store_true",
                   help="write the pages from the finished runs of the work directory only")
    args = p.parse_args()
    r = Runner(args)
    only = args.only.split(",") + (["tencate"] if args.tencate else [])
    sections = {}
    if "array3d" in only:
        sections[1] = []
        array3d(r, sections[1], [int(x) for x in args.array3d_levels.split(",")])
    if "array2d" in only:
        sections[2] = []
        array2d(r, sections[2])
    if "shear" in only:
        sections[3] = []
        shear(r, sections[3])
    if "wall" in only:
        sections[4] = []
        wall(r, sections[4])
    if "tencate" in only:
        sections[5] = []
        tencate(r, sections[5], args.tencate.split(","), args.tencate_meshes.split(","))
    if "closure" in only:
        sections[6] = []
        closure(r, sections[6])
    # Each section goes to its own file, so that parts can be regenerated separately;
    # doc/validation.md includes the discussion and links them.
    for k, text in sections.items():
        with open(os.path.join(DOC, "validation", f"section{k}.md"), "w") as f:
            f.write("\n".join(text))
    assemble()
    print(f"done in {(time.time() - r.started) / 60:.1f} min; wrote doc/validation.md")


HEADER = """# Validation against published results

How close fdparticle comes to published drag, rotation and settling numbers, and at what
cost.

`/usr/bin/python3 benchmarks/validation/run.py` regenerates sections 1–4 and 6 (~25 min on
2 cores; one section: `--only NAME`); `--tencate E1,E2,E3,E4` adds section 5 at d/h = 3 and 6
(10–60 min a case), `--tencate-meshes 5x8x5/2,5x8x5/3,7x11x7/3` also d/h = 8.25 (1.5–2.5 h
a case). It writes the sections below (doc/validation/section*.md), doc/validation/*.csv and
the plots; the discussion is doc/validation/discussion.md. References:
doc/references/README.md. Error = (ours − reference)/reference; d/h = particle diameter
over the cell size at its surface; wall time is the solver's own, on a shared 2-core
machine. Forces and torques come from λ (doc/method.md §9; with a fixed particle at steady
state F = −κ∫λ, κ the pairing weight of §3), which the periodic arrays check against the
exact balance F = f·|cell|.

"""


def assemble():
    parts = [HEADER]
    for k in range(1, 7):
        path = os.path.join(DOC, "validation", f"section{k}.md")
        if os.path.exists(path):
            with open(path) as f:
                parts.append(f.read().rstrip() + "\n\n")
    discussion = os.path.join(DOC, "validation", "discussion.md")
    if os.path.exists(discussion):
        with open(discussion) as f:
            parts.append(f.read())
    with open(os.path.join(DOC, "validation.md"), "w") as f:
        f.write("".join(parts))


if __name__ == "__main__":
    sys.exit(main())
