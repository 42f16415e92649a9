#!/usr/bin/env bash
# What the inertial term of S_p (Cahouet-Chabard's L, Solver/Pressure Laplacian; doc/method.md
# §8) buys and costs (doc/scaling.md, "The inertial term of S_p"): the sediment step of
# benchmarks/scaling_scenes.sh (flat n x 2n x n mesh, one rank) at several time steps, with
# L (true) and without (false). The box's slow pressure modes (wavenumber below
# k* = sqrt(rho_f c0/mu)) grow as the step shrinks; auto leaves L out with at most 10 of
# them and k* h <= 0.3 on the base mesh's cells. Writes
# doc/pressure_laplacian.csv: one row per case and variant with the slow modes, the outer
# and inner iterations, the preconditioner's set-up and iterating time, the step's wall
# time, the peak memory, the date and the commit.
# Usage: bash benchmarks/pressure_laplacian.sh   (~5 min on 2 cores; alone on the machine)
#        CASES="21:0.1" bash benchmarks/pressure_laplacian.sh   (n:dt pairs)
set -uo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
exe="${EXE:-$top/build/fdparticle}"
work="${WORK:-$top/benchmarks/work/pressure_laplacian}"
cases="${CASES:-6:1 6:0.1 8:0.1 12:1 12:0.1 12:0.05 12:0.01 12:0.001 21:0.1}"
[ -x "$exe" ] || bash "$top/scripts/build.sh"
mkdir -p "$work"
. "$top/benchmarks/scaling_scenes.sh"
csv="$top/doc/pressure_laplacian.csv"
date=$(date -u +%Y-%m-%d); commit=$(git -C "$top" rev-parse --short HEAD)

echo "n,time_step,laplacian,dofs,slow_pressure_modes,linear_iterations,inner_iterations,setup_seconds,iterate_seconds,step_seconds,peak_mb,date,commit" > "$csv"
for c in $cases; do
  n=${c%%:*} dt=${c##*:}
  for laplacian in true false; do
    d="$work/sediment-$n-$dt-$laplacian"
    mkdir -p "$d"
    { sediment "$n" | sed "s/Time step = .*/Time step = $dt/; s/End time = .*/End time = $dt/"
      printf 'subsection Solver\n  set Linear solver = iterative\n'
      printf '  set Iterative solver statistics = true\n  set Pressure Laplacian = %s\nend\n' "$laplacian"
      printf 'subsection Output\n  set Directory = %s\n  set VTU interval = 0\nend\n' "$d/out"
    } > "$d/scene.prm"
    if ! /usr/bin/time -f "%e %M" -o "$d/time" \
         bash "$top/scripts/mpirun.sh" 1 "$exe" "$d/scene.prm" > "$d/log" 2>&1; then
      echo "sediment $n, dt = $dt, Pressure Laplacian = $laplacian failed (see $d/log)"
      continue
    fi
    read -r wall kb < "$d/time"
    parts=$(/usr/bin/python3 "$top/scripts/solver-statistics.py" "$d/log" setup_seconds iterate_seconds)
    modes=$(/usr/bin/python3 "$top/scripts/solver-statistics.py" "$d/log" slow_pressure_modes)
    echo "$n,$dt,$laplacian,$(bash "$top/scripts/statistics-columns.sh" "$d/out/statistics.csv" last dofs),$modes,$(bash "$top/scripts/statistics-columns.sh" "$d/out/statistics.csv" last linear_iterations inner_iterations),$parts,$(bash "$top/scripts/statistics-columns.sh" "$d/out/statistics.csv" last wall_seconds),$((kb / 1024)),$date,$commit" | tee -a "$csv"
  done
done
