#!/usr/bin/env python3
"""Time series of benchmarks/suspension_time_3d.sh: one CSV row per step and a summary
on standard output.

Per step: the settling velocity U/U0 in the frame of zero volume flux, −(mean particle
v_z − mean v_z of the box) over Stokes' U0 = 2 Δρ g a²/(9 μ); the spread of the particle
velocities about their mean (σ of v_z and of the horizontal components, over U0); the
displacement of the spheres relative to each other since the start, as the RMS over the
spheres of their displacement less the mean displacement, in diameters (positions
unwrapped across the periodic faces: a step moves a sphere far less than half the box);
the contacts and the smallest gap of the step (statistics.csv); the Newton iterations and
the wall time of the step.

Usage: suspension_time_3d.py RUN_DIRECTORY BOX CSV
"""
import csv
import math
import sys
from collections import defaultdict

run, box, out = sys.argv[1], float(sys.argv[2]), sys.argv[3]
radius, viscosity, density_difference, gravity = 0.5, 1e4, 1.0, 1.0
u0 = 2 * density_difference * gravity * radius**2 / (9 * viscosity)

steps = list(csv.DictReader(open(f"{run}/statistics.csv")))
by_time = defaultdict(dict)
for r in csv.DictReader(open(f"{run}/particles.csv")):
    by_time[float(r["time"])][int(r["id"])] = r
times = sorted(by_time)
n = len(by_time[times[0]])
phi = n * 4 / 3 * math.pi * radius**3 / box**3


def unwrap(previous, now):
    """now moved by whole periods to the image nearest to previous."""
    return [c + box * round((p - c) / box) for p, c in zip(previous, now)]


# Unwrapped positions at every output time.
position = {0: {k: [float(by_time[times[0]][k][a]) for a in "xyz"] for k in range(n)}}
for i in range(1, len(times)):
    position[i] = {k: unwrap(position[i - 1][k], [float(by_time[times[i]][k][a]) for a in "xyz"])
                   for k in range(n)}


def relative_displacement(i):
    d = [[position[i][k][a] - position[0][k][a] for a in range(3)] for k in range(n)]
    mean = [sum(x[a] for x in d) / n for a in range(3)]
    return math.sqrt(sum(sum((x[a] - mean[a]) ** 2 for a in range(3)) for x in d) / n) / (2 * radius)


def spread(i, axes):
    values = [[float(by_time[times[i]][k][a]) for a in axes] for k in range(n)]
    total = 0.0
    for a in range(len(axes)):
        mean = sum(v[a] for v in values) / n
        total += sum((v[a] - mean) ** 2 for v in values) / n
    return math.sqrt(total / len(axes)) / u0


index_of = {t: i for i, t in enumerate(times)}
columns = ["step", "time", "settling_times", "u_over_u0", "sigma_vz_over_u0",
           "sigma_vh_over_u0", "relative_displacement", "contacts", "min_gap",
           "nonlinear_iterations", "seconds"]
rows = []
for s in steps:
    t = float(s["time"])
    i = index_of[t]
    rows.append({
        "step": int(s["step"]), "time": t, "settling_times": t * u0 / (2 * radius),
        "u_over_u0": -(float(s["mean_particle_vz"]) - float(s["mean_vz"])) / u0,
        "sigma_vz_over_u0": spread(i, ("vz",)), "sigma_vh_over_u0": spread(i, ("vx", "vy")),
        "relative_displacement": relative_displacement(i), "contacts": int(s["contacts"]),
        "min_gap": float(s["min_gap"]), "nonlinear_iterations": int(s["nonlinear_iterations"]),
        "seconds": float(s["wall_seconds"])})
with open(out, "w") as f:
    f.write(",".join(columns) + "\n")
    for r in rows:
        f.write(",".join(f"{r[c]:.6g}" if isinstance(r[c], float) else str(r[c])
                         for c in columns) + "\n")

u = [r["u_over_u0"] for r in rows]
half = len(rows) // 2
print(f"{n} spheres, solid fraction {phi:.4f}, {len(rows)} steps to t U0/d = "
      f"{rows[-1]['settling_times']:.2f}")
print(f"U/U0: first step {u[0]:.4f}, last {u[-1]:.4f}, mean over the second half "
      f"{sum(u[half:]) / len(u[half:]):.4f} (range {min(u[half:]):.4f}..{max(u[half:]):.4f}); "
      f"Richardson-Zaki (1 - phi)^4.65 = {(1 - phi) ** 4.65:.4f}, Batchelor 1 - 6.55 phi = "
      f"{1 - 6.55 * phi:.4f}")
print(f"relative displacement at the end {rows[-1]['relative_displacement']:.3f} d; sigma vz "
      f"{rows[0]['sigma_vz_over_u0']:.3f} -> {rows[-1]['sigma_vz_over_u0']:.3f} U0, horizontal "
      f"{rows[0]['sigma_vh_over_u0']:.3f} -> {rows[-1]['sigma_vh_over_u0']:.3f} U0")
print(f"steps with contacts {sum(r['contacts'] > 0 for r in rows)}, smallest gap "
      f"{min(r['min_gap'] for r in rows):.4f}; Newton iterations "
      f"{min(r['nonlinear_iterations'] for r in rows)}..{max(r['nonlinear_iterations'] for r in rows)}, "
      f"s/step {sum(r['seconds'] for r in rows) / len(rows):.1f} "
      f"({min(r['seconds'] for r in rows):.1f}..{max(r['seconds'] for r in rows):.1f})")
