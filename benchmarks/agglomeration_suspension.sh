#!/usr/bin/env bash
# Pressure agglomeration on a suspension without the cut-cell patch (doc/scaling.md, "Many
# particles: where the iterations go"): 25 spheres in the periodic box of edge 5 of
# benchmarks/suspension_scene.sh (seed 1, one Stokes step, iterative solver, Cut cell
# patch layers = -1) on CELLS cells a direction, with Quadrature/Pressure agglomeration =
# FRACTION. Writes doc/agglomeration_suspension.csv: one row per case with the FGMRES and
# inner iterations, the solve's iterating time, the run's wall time and peak memory, the
# settling velocity U (mean particle velocity minus the box's mean velocity, along
# gravity), the date and the commit.
# Usage: [CASES="10:0 10:0.25 ..."] bash benchmarks/agglomeration_suspension.sh
#        (~6 min on 2 cores with the default cases; alone on the machine)
set -uo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
exe="${EXE:-$top/build/fdparticle}"
work="${WORK:-$top/benchmarks/work/agglomeration_suspension}"
cases="${CASES:-10:0 10:0.25 10:0.5 10:0.75 15:0 15:0.5}"
[ -x "$exe" ] || bash "$top/scripts/build.sh"
. "$top/benchmarks/suspension_scene.sh"
csv="$top/doc/agglomeration_suspension.csv"
date=$(date -u +%Y-%m-%d); commit=$(git -C "$top" rev-parse --short HEAD)

echo "cells,agglomeration,dofs,linear_iterations,inner_iterations,iterate_seconds,run_seconds,peak_mb,settling_velocity,date,commit" > "$csv"
for c in $cases; do
  cells=${c%%:*} fraction=${c#*:}
  d="$work/$cells-$fraction"
  mkdir -p "$d"
  sections=$(printf 'subsection Solver\n  set Cut cell patch layers = -1\n  set Iterative solver statistics = true\nend\nsubsection Quadrature\n  set Pressure agglomeration = %s\nend\n' "$fraction")
  suspension_prm 25 5 "$cells" 1 iterative 1 1 BDF1 "$d/out" "$sections
" > "$d/scene.prm"
  if ! /usr/bin/time -f "%e %M" -o "$d/time" bash "$top/scripts/mpirun.sh" 1 "$exe" "$d/scene.prm" > "$d/log" 2>&1; then
    echo "$c failed (see $d/log)"
    continue
  fi
  read -r seconds kb < "$d/time"
  stats="$d/out/statistics.csv"
  u=$(bash "$top/scripts/statistics-columns.sh" "$stats" last mean_particle_vz mean_vz | awk -F, '{ printf "%.6e", $1 - $2 }')
  echo "$cells,$fraction,$(bash "$top/scripts/statistics-columns.sh" "$stats" last dofs linear_iterations inner_iterations),$(/usr/bin/python3 "$top/scripts/solver-statistics.py" "$d/log" iterate_seconds),$seconds,$((kb / 1024)),$u,$date,$commit" | tee -a "$csv"
done
