#!/usr/bin/env bash
# What sets the iterative solver's outer (FGMRES) count (doc/scaling.md, "What sets the
# outer count"): the sediment step of benchmarks/scaling_scenes.sh (flat n x 2n x n mesh,
# one rank) with the preconditioner's cheap form (the default), with J_w solved to 1e-8
# in every application (Cheap iterations = 0, Inner tolerance = 1e-8: the count then
# measures S_p and the patch alone), each also without the cut-cell patch, and each with
# the pressure of the nearly covered cut cells agglomerated (Quadrature/Pressure
# agglomeration = 0.25; the patch then grown from the inside cells alone). Writes
# doc/outer_count.csv: one row per variant with the outer and inner iterations, the
# patch's unknowns, the residual reached and the step's wall time, the date and the commit.
# Usage: [SIZES="8 12 16"] [VARIANTS="cheap exact ..."] [APPEND=1] bash benchmarks/outer_count.sh
#        (~8 min on 2 cores at the default SIZES=12, 40 min at "8 12 16"); APPEND=1 adds
#        rows to the CSV instead of starting it anew; a variant named twice runs twice.
set -uo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
exe="${EXE:-$top/build/fdparticle}"
work="${WORK:-$top/benchmarks/work/outer_count}"
sizes="${SIZES:-12}"
variants="${VARIANTS:-cheap exact cheap_without_patch exact_without_patch cheap_agglomerated exact_agglomerated cheap_agglomerated_without_patch exact_agglomerated_without_patch}"
[ -x "$exe" ] || bash "$top/scripts/build.sh"
mkdir -p "$work"
. "$top/benchmarks/scaling_scenes.sh"
csv="$top/doc/outer_count.csv"
date=$(date -u +%Y-%m-%d); commit=$(git -C "$top" rev-parse --short HEAD)

[ "${APPEND:-0}" = 1 ] ||
  echo "n,variant,dofs,linear_iterations,inner_iterations,patch_unknowns,relative_residual,step_seconds,date,commit" > "$csv"
for n in $sizes; do
  for variant in $variants; do
    d="$work/$variant-$n"
    mkdir -p "$d"
    { sediment "$n"
      printf 'subsection Solver\n  set Linear solver = iterative\n  set Iterative solver statistics = true\n'
      case $variant in exact*) printf '  set Cheap iterations = 0\n  set Inner tolerance = 1e-8\n' ;; esac
      case $variant in *without_patch) printf '  set Cut cell patch layers = -1\n' ;; esac
      case $variant in *agglomerated*) printf '  set Cut cell patch fluid fraction = 0\n' ;; esac
      printf 'end\nsubsection Quadrature\n  set Pressure agglomeration = %s\n' \
        "$(case $variant in *agglomerated*) echo 0.25 ;; *) echo 0 ;; esac)"
      printf 'end\nsubsection Output\n  set Directory = %s\n  set VTU interval = 0\nend\n' "$d/out"
    } > "$d/scene.prm"
    if ! bash "$top/scripts/mpirun.sh" 1 "$exe" "$d/scene.prm" > "$d/log" 2>&1; then
      echo "$variant failed (see $d/log)"
      continue
    fi
    residual=$(/usr/bin/python3 "$top/scripts/solver-statistics.py" "$d/log" relative_residual)
    patch=$(/usr/bin/python3 "$top/scripts/solver-statistics.py" "$d/log" patch_unknowns)
    echo "$n,$variant,$(bash "$top/scripts/statistics-columns.sh" "$d/out/statistics.csv" last dofs linear_iterations inner_iterations),$patch,$residual,$(bash "$top/scripts/statistics-columns.sh" "$d/out/statistics.csv" last wall_seconds),$date,$commit" | tee -a "$csv"
  done
done
