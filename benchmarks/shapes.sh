#!/usr/bin/env bash
# Ellipses and ellipsoids (doc/shapes.md).
#  1. Jeffery's orbit of an ellipse (tests/jeffery_ellipse_2d.prm): the scene as tested
#     (walls at y = +-1, 3 refinement levels, dt = 0.1), one level finer with half the time
#     step, and in a box twice as large with the same cells near the ellipse; the rate at the
#     ellipse's angle, the fastest rate and the time to turn against Jeffery's. Writes
#     doc/shapes_jeffery_2d.csv and doc/shapes_jeffery_2d.png.
#  2. What a shape costs (3D, tests/ellipsoid_equal_axes_3d.prm on 4 x 6 x 4 base cells
#     with the default level-set order and Navier-Stokes, 4 steps): the sphere, the same
#     sphere as an ellipsoid of equal semi-axes (the same cells: the cost of the general
#     shape's geometry) and a prolate spheroid 0.3 x 0.15 x 0.15 turned by 30 degrees (the
#     same d/h across its small axes); Jacobian assemblies, run time and peak memory.
#     Writes doc/shapes_cost_3d.csv.
#  3. With BASELINE=PATH (an fdparticle built from a commit before the shapes), sphere
#     scenes must not change or slow down: prm/sediment2d.prm and the sphere of 2., run by
#     both executables; whether particles.csv agrees to the last digit, and the run times.
#     Writes doc/shapes_sphere_regression.csv.
# Each row of the CSVs carries the date, the commit and the machine. About 4 minutes
# (6 with BASELINE), one rank; run it alone on the machine.
#
# Usage (regenerate):  bash benchmarks/shapes.sh
#                      BASELINE=../old/build/fdparticle bash benchmarks/shapes.sh
# EXE=PATH overrides the executable, WORK=DIR the work directory.
set -euo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
exe="${EXE:-$top/build/fdparticle}"
work="${WORK:-$top/benchmarks/work/shapes}"
mkdir -p "$work"
stamp="$(date -u +%Y-%m-%dT%H:%MZ),$(git -C "$top" rev-parse --short HEAD),$(hostname)"

run() { # name prm: run it, keep wall seconds and peak kB
  /usr/bin/time -f "%e %M" -o "$work/$1.time" "$exe" "$2" > "$work/$1.log" 2>&1 ||
    { echo "$1: the run failed: $(grep -m1 error "$work/$1.log")"; exit 1; }
}

derive() { # SRC OUT [OLD NEW]...: SRC without its '# test-' lines, each OLD replaced by NEW
  # (an empty NEW drops the line holding OLD). An OLD that SRC does not hold stops the
  # script: a changed test must not silently change the scene measured here.
  /usr/bin/python3 - "$@" <<'PY'
import sys
src, out, subs = sys.argv[1], sys.argv[2], sys.argv[3:]
text = "".join(l for l in open(src) if not l.startswith("# test-"))
for old, new in zip(subs[::2], subs[1::2]):
    if old not in text:
        sys.exit(f"shapes.sh: {src} no longer holds '{old}'; update the benchmark")
    if new:
        text = text.replace(old, new)
    else:
        text = "".join(l for l in text.splitlines(True) if old not in l)
open(out, "w").write(text)
PY
}

# 1. Jeffery's orbit.
jeffery="$top/tests/jeffery_ellipse_2d.prm"
for case in tested finer box; do
  case $case in
    tested) subs=() ;;
    finer)  subs=("Particle refinement levels = 3" "Particle refinement levels = 4"
                  "Time step = 0.1" "Time step = 0.05") ;;
    box)    subs=("Lower corner = -2, -1" "Lower corner = -4, -2"
                  "Upper corner = 2, 1" "Upper corner = 4, 2"
                  "Subdivisions = 16, 8" "Subdivisions = 32, 16"
                  "Wall velocities = y+: 1, 0; y-: -1, 0" "Wall velocities = y+: 2, 0; y-: -2, 0"
                  "End time = 8" "End time = 9") ;;
  esac
  derive "$jeffery" "$work/jeffery-$case.prm" "${subs[@]}"
  printf '\nsubsection Output\n  set Directory = %s\nend\n' "$work/jeffery-$case" >> "$work/jeffery-$case.prm"
  run "jeffery-$case" "$work/jeffery-$case.prm"
done

# 2. Cost of a shape.
scene="$top/tests/ellipsoid_equal_axes_3d.prm"
for case in sphere equal spheroid; do
  case $case in
    sphere)   shape="0.15" ;;
    equal)    shape="ellipsoid 0.15, 0.15, 0.15, 1, 2, 3, 30" ;;
    spheroid) shape="ellipsoid 0.3, 0.15, 0.15, 1, 2, 3, 30" ;;
  esac
  derive "$scene" "$work/cost-$case.prm" "set Convection = false" "" "set Level set order" "" \
         "Subdivisions = 3, 4, 3" "Subdivisions = 4, 6, 4" \
         "0.05, 0.3, 0.02 : 0.15 :" "0.05, 0.3, 0.02 : $shape :" "End time = 0.1" "End time = 0.2"
  printf '\nsubsection Output\n  set Directory = %s\nend\n' "$work/cost-$case" >> "$work/cost-$case.prm"
  run "cost-$case" "$work/cost-$case.prm"
done

# 3. Sphere scenes before and after.
if [ -n "${BASELINE:-}" ]; then
  derive "$top/prm/sediment2d.prm" "$work/sediment2d.prm" \
         "set Directory    = output/sediment2d" "set Directory = REPLACE"
  cp "$work/cost-sphere.prm" "$work/sphere3d.prm"
  for scene in sediment2d sphere3d; do
    for which in baseline current; do
      exe_now="$exe"; [ $which = baseline ] && exe_now="$BASELINE"
      sed "s|^  set Directory = .*|  set Directory = $work/$scene-$which|" "$work/$scene.prm" > "$work/$scene-$which.prm"
      /usr/bin/time -f "%e %M" -o "$work/$scene-$which.time" "$exe_now" "$work/$scene-$which.prm" \
        > "$work/$scene-$which.log" 2>&1
    done
  done
fi

/usr/bin/python3 - "$work" "$top/doc" "$stamp" <<'PY'
import csv, math, os, re, sys
work, doc, stamp = sys.argv[1:]
date, commit, machine = stamp.split(",")

def particles(d):
    return list(csv.DictReader(open(f"{d}/particles.csv")))

def unwrap(rows):
    theta = []
    for r in rows:
        a = float(r["rotz"])
        while theta and a - theta[-1] > math.pi: a -= 2 * math.pi
        while theta and a - theta[-1] < -math.pi: a += 2 * math.pi
        theta.append(a)
    return theta

a, b = 0.2, 0.1
def rate(th, G): return -G * (a * a * math.sin(th) ** 2 + b * b * math.cos(th) ** 2) / (a * a + b * b)
def phase(th, G):
    k = G * a * b / (a * a + b * b)
    turns = math.floor((-th + math.pi / 2) / math.pi)
    return (math.atan(-(a / b) * math.tan(th + turns * math.pi)) + turns * math.pi) / k

rows_out, curves = [], {}
for case, H, levels, dt in (("tested", 2, 3, 0.1), ("finer", 2, 4, 0.05), ("box", 4, 3, 0.1)):
    G = 1.0
    rows = particles(f"{work}/jeffery-{case}")
    t = [float(r["time"]) for r in rows]; th = unwrap(rows); w = [float(r["wz"]) for r in rows]
    dev = [i for i, x in enumerate(t) if x >= (1.0 if H == 2 else 2.0)]
    worst = max(abs(w[i] / rate(th[i], G) - 1) for i in dev)
    fastest = max(-w[i] for i in dev) / (G * a * a / (a * a + b * b)) - 1
    took = t[dev[-1]] - t[dev[0]]
    expected = phase(th[dev[-1]], G) - phase(th[dev[0]], G)
    seconds, kb = open(f"{work}/jeffery-{case}.time").read().split()
    h = (4.0 * H / 2) / (16 * H / 2) / 2 ** levels
    rows_out.append(dict(case=case, box_height=H, b_over_h=b / h, dt=dt,
                         turned_rad=round(th[dev[0]] - th[dev[-1]], 4),
                         turning_time_error=round(took / expected - 1, 5),
                         fastest_rate_error=round(fastest, 5), worst_rate_error=round(worst, 5),
                         wall_seconds=seconds, peak_mb=round(int(kb) / 1024), date=date,
                         commit=commit, machine=machine))
    curves[case] = (t, th, w)
with open(f"{doc}/shapes_jeffery_2d.csv", "w", newline="") as f:
    wr = csv.DictWriter(f, fieldnames=list(rows_out[0])); wr.writeheader(); wr.writerows(rows_out)
for r in rows_out: print("jeffery", r)

cost = []
for case in ("sphere", "equal", "spheroid"):
    log = open(f"{work}/cost-{case}.log").read()
    m = re.search(r"\| assemble system\s*\|\s*(\d+)\s*\|\s*([\d.]+)s", log)
    dofs = re.search(r"(\d+) finite-element DoFs", log).group(1)
    seconds, kb = open(f"{work}/cost-{case}.time").read().split()
    cost.append(dict(case=case, dofs=dofs, jacobians=m.group(1),
                     seconds_per_jacobian=round(float(m.group(2)) / int(m.group(1)), 4),
                     wall_seconds=seconds, peak_mb=round(int(kb) / 1024), date=date,
                     commit=commit, machine=machine))
with open(f"{doc}/shapes_cost_3d.csv", "w", newline="") as f:
    wr = csv.DictWriter(f, fieldnames=list(cost[0])); wr.writeheader(); wr.writerows(cost)
for r in cost: print("cost", r)

if os.path.exists(f"{work}/sphere3d-baseline.time"):
    rows = []
    for scene in ("sediment2d", "sphere3d"):
        runs = {w: list(csv.DictReader(open(f"{work}/{scene}-{w}/particles.csv")))
                for w in ("baseline", "current")}
        common = [c for c in runs["baseline"][0] if c in runs["current"][0] and c != "wall_seconds"]
        same = len(runs["baseline"]) == len(runs["current"]) and all(
            a[c] == b[c] for a, b in zip(runs["baseline"], runs["current"]) for c in common)
        t = {w: open(f"{work}/{scene}-{w}.time").read().split() for w in ("baseline", "current")}
        rows.append(dict(scene=scene, particles_csv_identical=same,
                         baseline_seconds=t["baseline"][0], current_seconds=t["current"][0],
                         ratio=round(float(t["current"][0]) / float(t["baseline"][0]), 3),
                         baseline_peak_mb=round(int(t["baseline"][1]) / 1024),
                         current_peak_mb=round(int(t["current"][1]) / 1024),
                         date=date, commit=commit, machine=machine))
    with open(f"{doc}/shapes_sphere_regression.csv", "w", newline="") as f:
        wr = csv.DictWriter(f, fieldnames=list(rows[0])); wr.writeheader(); wr.writerows(rows)
    for r in rows: print("sphere scenes", r)

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2))
k = a * b / (a * a + b * b)
ts = [i * 0.02 for i in range(451)]
left.plot(ts, [-(math.atan((b / a) * math.tan(k * x)) + math.pi * math.floor((k * x + math.pi / 2) / math.pi))
              for x in ts],
          "k-", lw=2.5, alpha=0.35, label="Jeffery (fluid at rest at t = 0 aside)")
labels = {"tested": "H = 2, b/h = 3.2 (ctest)", "finer": "H = 2, b/h = 6.4, dt/2", "box": "H = 4, b/h = 3.2"}
for case, (t, th, w) in curves.items():
    left.plot(t, th, label=labels[case])
    right.plot([-x for x in th[5:]], [wi / rate(x, 1.0) for wi, x in zip(w[5:], th[5:])], label=labels[case])
left.set_xlabel("t G"); left.set_ylabel("angle of the long axis (rad)"); left.legend(fontsize=8)
right.axhline(1, color="k", lw=0.8)
right.set_xlabel("angle turned (rad)"); right.set_ylabel("angular velocity / Jeffery's"); right.legend(fontsize=8)
fig.suptitle("An ellipse (a/b = 2) in simple shear: Jeffery's orbit")
fig.tight_layout(); fig.savefig(f"{doc}/shapes_jeffery_2d.png", dpi=110)
PY
