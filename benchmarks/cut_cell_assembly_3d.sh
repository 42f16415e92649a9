#!/usr/bin/env bash
# Cost and accuracy of the cut-cell rule in 3D (doc/method.md §7): 8 free spheres
# (R = 0.12, density 1.5) in the 1 x 2 x 1 box on 6 x 12 x 6 cells refined once around
# them (R/h = 1.4), Stokes, two BDF steps of 0.1, one rank, for the Gauss rule with 7
# points and the level-set rules of order 2, 3, 4, 6 and 8 (RULES).
# Writes doc/cut_cell_assembly_3d.csv: per executable and rule, the largest relative
# change of a sphere velocity against the same executable's order 8 after the two steps,
# the Jacobian and residual assembly per call (TimerOutput), the whole run and peak memory;
# and the plot doc/cut_cell_assembly_3d.png (Jacobian assembly per call).
#
# Usage (regenerate):  bash benchmarks/cut_cell_assembly_3d.sh
# EXES="name=PATH ..." compares executables in one run (default: new=build/fdparticle);
# WORK=DIR the work directory, RULES="gauss7 level6" the rules.
set -euo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
exes="${EXES:-new=$top/build/fdparticle}"
work="${WORK:-$top/benchmarks/work/cut_cell_assembly_3d}"
rules="${RULES:-gauss7 level2 level3 level4 level6 level8}"
mkdir -p "$work"
csv="$top/doc/cut_cell_assembly_3d.csv"
echo "executable,rule,velocity_change_vs_order_8,jacobian_seconds_per_call,residual_seconds_per_call,run_seconds,peak_MB" > "$csv"

scene() { # rule output-directory
  local quadrature
  case "$1" in
    gauss*) quadrature="  set Cut cells = gauss
  set Gauss points in cut cells = ${1#gauss}" ;;
    level*) quadrature="  set Cut cells = level set
  set Level set order = ${1#level}" ;;
  esac
  local spheres="" x y z
  for y in 0.3 0.9; do for z in -0.22 0.22; do for x in -0.22 0.22; do
    spheres="${spheres:+$spheres ; }$x, $y, $z : 0.12 : 1.5"
  done; done; done
  cat <<PRM
set Dimension = 3
set Gravity = 0, -10, 0
subsection Geometry
  set Lower corner = -0.5, -0.5, -0.5
  set Upper corner = 0.5, 1.5, 0.5
  set Subdivisions = 6, 12, 6
end
subsection Refinement
  set Particle refinement levels = 1
end
subsection Fluid
  set Density = 1
  set Viscosity = 1
  set Convection = false
end
subsection Particles
  set Particles = $spheres
end
subsection Quadrature
$quadrature
end
subsection Time
  set End time = 0.2
  set Time step = 0.1
end
subsection Output
  set VTU interval = 0
  set Directory = $2
end
PRM
}

for entry in $exes; do
  name="${entry%%=*}"
  exe="${entry#*=}"
  # Order 8 first: the reference of this executable's velocity changes.
  for rule in level8 $(printf '%s\n' $rules | grep -vx level8); do
    run="$name-$rule"
    scene "$rule" "$work/$run" > "$work/$run.prm"
    /usr/bin/time -f "%e %M" -o "$work/$run.time" "$exe" "$work/$run.prm" > "$work/$run.log"
  done
  for rule in $rules; do
    /usr/bin/python3 - "$work" "$name" "$rule" >> "$csv" <<'PY'
import csv, re, sys
work, name, rule = sys.argv[1:4]
log = open(f"{work}/{name}-{rule}.log").read()
def per_call(section):
    m = re.search(r"\|\s*" + section + r"\s*\|\s*(\d+)\s*\|\s*([0-9.]+)(m?s)", log)
    return float(m.group(2)) / (1000 if m.group(3) == "ms" else 1) / int(m.group(1))
def last_velocities(run):
    rows = list(csv.DictReader(open(f"{work}/{run}/particles.csv")))
    t = rows[-1]["time"]
    return [[float(r[k]) for k in ("vx", "vy", "vz")] for r in rows if r["time"] == t]
ref = last_velocities(f"{name}-level8")
change = max(sum((a - b) ** 2 for a, b in zip(v, w)) ** 0.5 / sum(b * b for b in w) ** 0.5
             for v, w in zip(last_velocities(f"{name}-{rule}"), ref))
seconds, kb = open(f"{work}/{name}-{rule}.time").read().split()[-2:]
print(f"{name},{rule},{change:.2e},{per_call('assemble system'):.2f},"
      f"{per_call('assemble residual'):.2f},{float(seconds):.1f},{int(kb) / 1024:.0f}")
PY
    tail -1 "$csv"
  done
done

gnuplot <<GNUPLOT
set terminal pngcairo size 700,450
set output "$top/doc/cut_cell_assembly_3d.png"
set datafile separator ","
set style data histograms
set style fill solid 0.6 border -1
set ylabel "Jacobian assembly per call [s]"
set yrange [0:*]
set key top left
plot for [e in "$(for entry in $exes; do printf '%s ' "${entry%%=*}"; done)"] \
  "< grep '^".e.",' $csv" using 4:xticlabels(2) title e
GNUPLOT
