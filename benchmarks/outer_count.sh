#!/usr/bin/env bash
# What sets the iterative solver's outer (FGMRES) count (doc/scaling.md, "What sets the
# outer count"): the sediment step of benchmarks/scaling_scenes.sh (flat n x 2n x n mesh,
# one rank) with the preconditioner's cheap form (the default), with J_w solved to 1e-8
# in every application (Cheap iterations = 0, Inner tolerance = 1e-8: the count then
# measures S_p and the patch alone), and the same without the cut-cell patch. Writes
# doc/outer_count.csv: one row per variant with the outer and inner iterations, the
# residual reached and the step's wall time, the date and the commit.
# Usage: bash benchmarks/outer_count.sh   (~4 min on 2 cores at the default N=12)
set -uo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
exe="${EXE:-$top/build/fdparticle}"
work="${WORK:-$top/benchmarks/work/outer_count}"
n="${N:-12}"
[ -x "$exe" ] || bash "$top/scripts/build.sh"
mkdir -p "$work"
. "$top/benchmarks/scaling_scenes.sh"
csv="$top/doc/outer_count.csv"
date=$(date -u +%Y-%m-%d); commit=$(git -C "$top" rev-parse --short HEAD)

echo "n,variant,dofs,linear_iterations,inner_iterations,relative_residual,step_seconds,date,commit" > "$csv"
for variant in cheap exact exact_without_patch; do
  d="$work/$variant-$n"
  mkdir -p "$d"
  { sediment "$n"
    printf 'subsection Solver\n  set Linear solver = iterative\n  set Iterative solver statistics = true\n'
    case $variant in
      exact) printf '  set Cheap iterations = 0\n  set Inner tolerance = 1e-8\n' ;;
      exact_without_patch)
        printf '  set Cheap iterations = 0\n  set Inner tolerance = 1e-8\n  set Cut cell patch layers = -1\n' ;;
    esac
    printf 'end\nsubsection Output\n  set Directory = %s\n  set VTU interval = 0\nend\n' "$d/out"
  } > "$d/scene.prm"
  if ! bash "$top/scripts/mpirun.sh" 1 "$exe" "$d/scene.prm" > "$d/log" 2>&1; then
    echo "$variant failed (see $d/log)"
    continue
  fi
  residual=$(/usr/bin/python3 "$top/scripts/solver-statistics.py" "$d/log" relative_residual)
  echo "$n,$variant,$(bash "$top/scripts/statistics-columns.sh" "$d/out/statistics.csv" last dofs linear_iterations inner_iterations),$residual,$(bash "$top/scripts/statistics-columns.sh" "$d/out/statistics.csv" last wall_seconds),$date,$commit" | tee -a "$csv"
done
