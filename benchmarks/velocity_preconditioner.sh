#!/usr/bin/env bash
# The velocity block inside the iterative solver's block preconditioner: one ML V-cycle on
# the assembled A_uu (Solver/Velocity preconditioner = amg) against the geometric multigrid
# on the matrix-free operator (= multigrid), whole Newton solves of the program, 1 and 2
# ranks. Scenes (3D):
#  - sediment n: the one-step Stokes sediment of benchmarks/scaling_scenes.sh on the same
#    n x 2n x n mesh, built as a 3 x 6 x 3 (or 1 x 2 x 1) base mesh refined globally, so
#    that the multigrid has mesh levels below it (n = 12, 16, 24: 198 k, 457 k, 1.51 M unknowns);
#  - flat n: the same scene on an n x 2n x n base mesh, as benchmarks/scaling.sh runs it:
#    no mesh level below it, so the multigrid has two levels, Q2 and Q1 on that mesh;
#  - array k: prm/validation/array3d.prm (fixed sphere, periodic cube, steady Stokes, two
#    particle refinement levels: hanging nodes) with k global refinements.
# One row of doc/velocity_preconditioner.csv per run: unknowns, multigrid levels, FGMRES
# (inner) iterations, the step's and the run's wall time, peak memory of the largest rank, and from
# the statistics line the preconditioner's set-up (its patch's part), the iterations'
# time, its velocity V-cycles' and operator products' parts, and the non-zeros of the
# Newton matrix (with multigrid it holds no velocity block). Compare within one run, alone on the machine.
# Usage: bash benchmarks/velocity_preconditioner.sh   (~45 min on 2 cores; 9 GB at n = 24)
# CASES="sediment:12 array:0" overrides the scenes, EXE the program; APPEND=1 adds the
# rows to the CSV instead of starting it anew.
set -uo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
exe="${EXE:-$top/build/fdparticle}"
work="${WORK:-$top/benchmarks/work/velocity_preconditioner}"
cases="${CASES:-sediment:12 sediment:16 sediment:24 flat:12 flat:24 array:0 array:1}"
[ -x "$exe" ] || bash "$top/scripts/build.sh"
mkdir -p "$work"
. "$top/benchmarks/scaling_scenes.sh"
csv="$top/doc/velocity_preconditioner.csv"
date=$(date -u +%Y-%m-%d); commit=$(git -C "$top" rev-parse --short HEAD)

scene() { # kind size
  case "$1" in
    sediment)
      local base=3 k=0 m=$2
      [ $(($2 % 3)) -ne 0 ] && base=1
      while [ $((base << k)) -lt "$2" ]; do k=$((k + 1)); done
      sediment "$2" | sed "s/^  set Subdivisions = .*/  set Subdivisions = $base, $((2 * base)), $base\n  set Global refinements = $k/" ;;
    flat)
      sediment "$2" ;;
    array)
      sed "s/^  set Global refinements .*/  set Global refinements = $2/" "$top/prm/validation/array3d.prm" ;;
  esac
}

[ "${APPEND:-0}" = 1 ] ||
echo "scene,size,ranks,velocity_preconditioner,dofs,levels,linear_iterations,inner_iterations,step_seconds,wall_seconds,peak_mb,setup_seconds,patch_setup_seconds,iterate_seconds,velocity_cycle_seconds,product_seconds,matrix_nonzeros,date,commit" > "$csv"
for c in $cases; do
  kind=${c%:*}; size=${c#*:}
  for ranks in 1 2; do
    for vp in amg multigrid; do
      d="$work/$kind-$size-$ranks-$vp"
      mkdir -p "$d"
      { scene "$kind" "$size"
        printf 'subsection Solver\n  set Linear solver = iterative\n  set Velocity preconditioner = %s\n' "$vp"
        printf '  set Iterative solver statistics = true\nend\n'
        printf 'subsection Output\n  set Directory = %s\n  set VTU interval = 0\nend\n' "$d/out"
      } > "$d/scene.prm"
      if ! /usr/bin/time -f "%e %M" -o "$d/time" \
           bash "$top/scripts/mpirun.sh" "$ranks" "$exe" "$d/scene.prm" > "$d/log" 2>&1; then
        echo "$kind $size, $vp, on $ranks ranks failed (see $d/log)"
        continue
      fi
      read -r wall kb < "$d/time"
      # The mesh's levels and the Q1 level below them.
      levels=$(awk '/^  set Global refinements/ {g = $5} /^  set Particle refinement levels/ {p = $6}
                    END {print g + p + 2}' "$d/scene.prm")
      [ "$vp" = amg ] && levels=1
      parts=$(/usr/bin/python3 "$top/scripts/solver-statistics.py" "$d/log" setup_seconds \
        patch_setup_seconds iterate_seconds velocity_cycle_seconds product_seconds \
        matrix_nonzeros)
      echo "$kind,$size,$ranks,$vp,$(bash "$top/scripts/statistics-columns.sh" "$d/out/statistics.csv" last dofs),$levels,$(bash "$top/scripts/statistics-columns.sh" "$d/out/statistics.csv" last linear_iterations inner_iterations wall_seconds),$wall,$((kb / 1024)),$parts,$date,$commit" | tee -a "$csv"
    done
  done
done
column -s, -t "$csv"
