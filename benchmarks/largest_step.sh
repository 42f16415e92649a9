#!/usr/bin/env bash
# The largest 3D step that fits this machine (doc/scaling.md, "The largest step"): the
# sediment step of benchmarks/scaling_scenes.sh, iterative solver, on RANKS ranks (default
# 1, the least memory per unknown) at each n of SIZES, with the cut-cell patch allowed
# PATCH_GB (default 8) and `Iterative solver statistics`. Appends one row per run to
# doc/largest_step.csv (date, commit, n, ranks, unknowns, FGMRES and inner iterations, the
# step's and the run's wall time, peak memory of the largest rank, the preconditioner's
# set-up and the iterations with the patch's part of each, the patch's unknowns and
# factors); a run that fails (out of memory) is reported and not written. Run alone.
# Usage: SIZES="32 43" bash benchmarks/largest_step.sh   (n = 43: 8.5 M unknowns)
set -uo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
exe="${EXE:-$top/build/fdparticle}"
work="${WORK:-$top/benchmarks/work/largest_step}"
sizes="${SIZES:-32 43}"
ranks="${RANKS:-1}"
patch_gb="${PATCH_GB:-8}"
[ -x "$exe" ] || bash "$top/scripts/build.sh"
mkdir -p "$work"
. "$top/benchmarks/scaling_scenes.sh"

csv="$top/doc/largest_step.csv"
[ -f "$csv" ] || echo "date,commit,n,ranks,dofs,linear_iterations,inner_iterations,step_seconds,wall_seconds,peak_mb,setup_seconds,patch_setup_seconds,iterate_seconds,patch_apply_seconds,patch_unknowns,patch_mb" > "$csv"
commit=$(git -C "$top" rev-parse --short HEAD 2>/dev/null || echo unknown)
for n in $sizes; do
  d="$work/sediment-$n-$ranks"
  mkdir -p "$d"
  { sediment "$n"
    printf 'subsection Solver\n  set Linear solver = iterative\n'
    printf '  set Iterative solver statistics = true\n  set Cut cell patch memory = %s\nend\n' "$patch_gb"
    printf 'subsection Output\n  set Directory = %s\n  set VTU interval = 0\nend\n' "$d/out"
  } > "$d/scene.prm"
  if ! /usr/bin/time -f "%e %M" -o "$d/time" \
       bash "$top/scripts/mpirun.sh" "$ranks" "$exe" "$d/scene.prm" > "$d/log" 2>&1; then
    echo "sediment $n on $ranks rank(s) failed (see $d/log)"
    continue
  fi
  read -r wall kb < <(tail -1 "$d/time")
  parts=$(/usr/bin/python3 "$top/scripts/solver-statistics.py" "$d/log" setup_seconds \
    patch_setup_seconds iterate_seconds patch_apply_seconds patch_unknowns patch_mb)
  echo "$(date -u +%F),$commit,$n,$ranks,$(bash "$top/scripts/statistics-columns.sh" "$d/out/statistics.csv" last dofs linear_iterations inner_iterations wall_seconds),$wall,$((kb / 1024)),$parts" | tee -a "$csv"
done
