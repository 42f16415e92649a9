#!/usr/bin/env python3
"""The force on a turning ellipse (2D) or spheroid (3D) as it moves through the mesh, against
a disk (ball) of the same area (volume): its convergence in h (tools/fdparticle-study) and
the smoothness of its history (the measure S of doc/method.md, "Smoothness measure", with
the force F in place of the velocity).

The shape moves with prescribed velocity (0.5, 0[, 0]) and turns at angular velocity 1
about z between no-slip walls at y = -1 and 1, periodic along x (and z), Stokes flow,
mu = rho = 1, level-set cut cells, the mesh refined around the shape. Over a half turn
(t = pi) it crosses 6 cells of the base mesh. The exact force on the disk is constant once
the start-up has decayed; on the ellipse it changes with the angle at twice the rate of
turn. S is taken over t >= 1 (the start-up decays on the viscous time L^2/nu = 1);
S_smooth is S of the ellipse's force fitted by a Fourier series in the angle (up to the
fourth harmonic of 2 theta): the part of S the turning itself makes.

Writes doc/shapes_force.csv (each row with the date and the build of its run),
doc/shapes_force.png, and prints a Markdown table; the studies go to
benchmarks/work/shape_force/ (--reuse keeps finished runs). Run alone (2D: about 10 minutes
on one rank; --dims 2,3 adds the 3D study, about an hour):
    /usr/bin/python3 benchmarks/shape_force.py [--dims 2] [--reuse]
"""
import argparse
import csv
import math
import os
import subprocess
import sys

import numpy as np

TOP = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(TOP, "tests"))
from testlib import run_provenance  # noqa: E402  (after the path it lives on)
END = 3.14  # a half turn at angular velocity 1
START = 1.0  # S over t >= START

def scene(dim, shape, end):
    """The prm text of the scene in dim dimensions for the given shape entry."""
    d3 = dim == 3
    zero, corner = ("0, 0, 0", "1, 1, 1") if d3 else ("0, 0", "1, 1")
    motion = "0.5, 0, 0 : 0, 0, 1" if d3 else "0.5, 0 : 1"
    return f"""set Dimension = {dim}
set Gravity = {zero}
subsection Geometry
  set Lower corner = -{corner.replace(', ', ', -')}
  set Upper corner = {corner}
  set Subdivisions = {"6, 6, 6" if d3 else "8, 8"}
  set Periodic directions = {"x, z" if d3 else "x"}
end
subsection Fluid
  set Density = 1
  set Viscosity = 1
  set Convection = false
end
subsection Particles
  set Particles = {zero} : {shape} : 1 : prescribed : {motion}
end
subsection Quadrature
  set Cut cells = level set
end
subsection Solver
  set Linear solver = {"iterative" if d3 else "direct"}
end
subsection Time
  set Time step = {0.05 if d3 else 0.02}
  set End time = {end}
end
subsection Output
  set VTU interval = 0
end
"""


# The shape and the ball of the same area (volume): a b = r^2 in 2D, a b c = r^3 in 3D.
SHAPES = {
    2: [("ellipse", "ellipse 0.2, 0.1, 0"), ("disk", f"{math.sqrt(0.2 * 0.1):.6f}")],
    3: [("spheroid", "ellipsoid 0.2, 0.1, 0.1"), ("ball", f"{(0.2 * 0.1 * 0.1) ** (1 / 3):.6f}")],
}
LEVELS = {2: "2,3,4,5", 3: "2,3"}
# The semi-axis b over the finest cell at Particle refinement level L: b / (H / 2^L).
BASE_CELL = {2: 2 / 8, 3: 2 / 6}


def smoothness(t, f):
    """S of doc/method.md for the history f (rows: steps) over t >= START."""
    f = f[t >= START]
    second = f[2:] - 2 * f[1:-1] + f[:-2]
    rms = lambda x: math.sqrt(np.mean(np.sum(x * x, axis=1)))
    return rms(second) / rms(f[1:-1])


def fourier_fit(t, f, harmonics=4):
    """f fitted by a Fourier series in 2 theta = 2 t (the turn's period is pi)."""
    columns = [np.ones_like(t)]
    for k in range(1, harmonics + 1):
        columns += [np.cos(2 * k * t), np.sin(2 * k * t)]
    basis = np.stack(columns, axis=1)
    coefficients, *_ = np.linalg.lstsq(basis, f, rcond=None)
    return basis @ coefficients


def read_history(run_dir, dim):
    with open(os.path.join(run_dir, "output", "particles.csv")) as f:
        rows = list(csv.DictReader(f))
    t = np.array([float(r["time"]) for r in rows])
    force = np.array([[float(r[c]) for c in ("fx", "fy", "fz")[:dim]] for r in rows])
    torque = np.array([float(r["tz"]) for r in rows])
    return t, force, torque


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--dims", default="2")
    parser.add_argument("--reuse", action="store_true")
    parser.add_argument("--executable", default=os.path.join(TOP, "build", "fdparticle"))
    parser.add_argument("--work", default=os.path.join(TOP, "benchmarks", "work", "shape_force"))
    opts = parser.parse_args()
    os.makedirs(opts.work, exist_ok=True)
    rows, histories = [], {}
    for dim in [int(d) for d in opts.dims.split(",")]:
        for name, shape in SHAPES[dim]:
            study = os.path.join(opts.work, f"{dim}d-{name}")
            prm = study + ".prm"
            with open(prm, "w") as f:
                f.write(scene(dim, shape, END))
            command = ["/usr/bin/python3", os.path.join(TOP, "tools", "fdparticle-study"), prm,
                       "--output", study, "--executable", opts.executable,
                       "--vary", f"Refinement/Particle refinement levels={LEVELS[dim]}",
                       "--qoi", f"terminal-fx,fx-at:{END}",
                       "--terminal-fraction", f"{(END - START) / END:.4f}"]
            if opts.reuse:
                command.append("--reuse")
            subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
            with open(os.path.join(study, "study.csv")) as f:
                study_rows = list(csv.DictReader(f))
            for s in study_rows:
                level = int(s["Refinement/Particle refinement levels"])
                run_dir = os.path.join(study, "runs", f"run-{int(s['run']):03d}")
                t, force, torque = read_history(run_dir, dim)
                row = {"dim": dim, "shape": name, "levels": level,
                       "b_over_h": round(0.1 / (BASE_CELL[dim] / 2 ** level), 2),
                       "dofs": s["dofs"], "wall_seconds": round(float(s["wall_seconds"]), 1),
                       "fx_mean": f"{float(s['qoi']):.6g}",
                       "fx_mean_relative_error": s["relative_error"],
                       "fx_mean_reference": s["reference_source"],
                       "fx_end": f"{force[-1, 0]:.6g}",
                       "fx_end_relative_error": s[f"relative_error:fx-at:{END}"],
                       "S_force": f"{smoothness(t, force):.3g}"}
                if name in ("ellipse", "spheroid"):
                    keep = t >= START
                    fit = np.stack([fourier_fit(t[keep], force[keep, c]) for c in range(dim)],
                                   axis=1)
                    row["S_smooth"] = f"{smoothness(t[keep], fit):.3g}"
                else:
                    row["S_smooth"] = "0"
                when, built = run_provenance(os.path.join(run_dir, "output"))
                row.update({"date": when, "revision": built})
                rows.append(row)
                histories[(dim, name, level)] = (t, force)
    out = os.path.join(TOP, "doc", "shapes_force.csv")
    with open(out, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    dims = sorted({d for d, _, _ in histories})
    fig, axes = plt.subplots(len(dims), 2, figsize=(12, 4.2 * len(dims)), squeeze=False)
    for row, dim in zip(axes, dims):
        for (d, name, level), (t, force) in sorted(histories.items()):
            if d != dim:
                continue
            keep = t >= START
            style = "-" if name in ("ellipse", "spheroid") else "--"
            label = f"{name}, b/h = {0.1 / (BASE_CELL[dim] / 2 ** level):.3g}"
            row[0].plot(t[keep], force[keep, 0], style, lw=1, label=label)
            # What S measures: the force less its smooth part (the fit in the angle).
            jitter = force[keep, 0] - fourier_fit(t[keep], force[keep, 0])
            row[1].plot(t[keep], jitter, style, lw=1, label=label)
        row[0].set_ylabel("F_x")
        row[0].set_title(f"{dim}D: force on the turning shape and on the ball")
        row[1].set_ylabel("F_x less its Fourier fit in the angle")
        row[1].set_title(f"{dim}D: the part that is not smooth")
        for ax in row:
            ax.set_xlabel("t (the shape has turned by t radians)")
            ax.grid(alpha=0.3)
            ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(TOP, "doc", "shapes_force.png"), dpi=110)

    percent = lambda e: f"{100 * float(e):.2f}" if e not in ("", None) else ""
    print("| dim | shape | b/h | DoFs | mean F_x | error % | F_x(pi) | error % | S | S of the "
          "turn | s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['dim']} | {r['shape']} | {r['b_over_h']} | {r['dofs']} | {r['fx_mean']} | "
              f"{percent(r['fx_mean_relative_error'])} | {r['fx_end']} | "
              f"{percent(r['fx_end_relative_error'])} | {r['S_force']} | {r['S_smooth']} | "
              f"{r['wall_seconds']} |")


if __name__ == "__main__":
    main()
