#!/usr/bin/env bash
# Cost of a step of the adaptive 3D runs of doc/smoothness.md (variant adaptls: level-set
# cut cells, 2 particle refinement levels) with the direct and the iterative linear solver:
#   sediment  prm/sediment.prm (Δt = 0.1; the smoothness run goes to t = 100), SED_STEPS steps
#   cavity    prm/cavity.prm (Δt = 0.01; the smoothness run goes to t = 5), CAV_STEPS steps
# on each rank count of RANKS. Writes doc/adaptive_step_cost.csv, one row per run: unknowns,
# steps, Newton and FGMRES iterations (direct solver: solves) per step, the mean wall time of
# a step after the first (the first starts the flow from rest and, with the direct solver,
# analyses the matrix), the hours to the smoothness run's end time at that rate, the run's
# wall time and peak memory of one rank, and for the iterative solver its totals over the
# run (scripts/solver-statistics.py --run): preconditioner set-up and the patch's part,
# iterating and the patch's part; then the date and the commit.
# Usage: [RANKS="1 2"] [SED_STEPS=3] [CAV_STEPS=6] bash benchmarks/adaptive_step_cost.sh
#        (~33 min with both rank counts, 17 GB; alone on the machine: compare within one run)
set -uo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
exe="${EXE:-$top/build/fdparticle}"
work="${WORK:-$top/benchmarks/work/adaptive_step_cost}"
ranks_list="${RANKS:-1 2}"
[ -x "$exe" ] || bash "$top/scripts/build.sh"
mkdir -p "$work"
. "$top/benchmarks/scaling_scenes.sh"
csv="$top/doc/adaptive_step_cost.csv"
date=$(date -u +%Y-%m-%d); commit=$(git -C "$top" rev-parse --short HEAD)

scene() { # name solver directory -> prm on stdout
  local dt steps
  case $1 in
    sediment) dt=0.1;  steps=${SED_STEPS:-3} ;;
    cavity)   dt=0.01; steps=${CAV_STEPS:-6} ;;
  esac
  sed -e "s#^\(\s*set Directory\s*=\).*#\1 $3#" -e "s/^\(\s*set VTU interval\s*=\).*/\1 0/" \
      -e "s/^\(\s*set End time\s*=\).*/\1 $(awk -v a="$dt" -v b="$steps" "BEGIN { print a * b }")/" "$top/prm/$1.prm"
  adaptive_levelset
  printf 'subsection Solver\n  set Linear solver = %s\n  set Iterative solver statistics = true\nend\n' "$2"
}

end_time() { case $1 in sediment) echo 100 ;; cavity) echo 5 ;; esac; }

echo "scene,solver,ranks,dofs_first,dofs_last,steps,newton_per_step,linear_per_step,step_seconds,hours_to_end,run_seconds,peak_mb,setup_seconds,patch_setup_seconds,iterate_seconds,patch_apply_seconds,date,commit" > "$csv"
for name in sediment cavity; do
  for ranks in $ranks_list; do
    for solver in direct iterative; do
      d="$work/$name-$solver-$ranks"
      rm -rf "$d"; mkdir -p "$d"
      scene "$name" "$solver" "$d/out" > "$d/scene.prm"
      if ! /usr/bin/time -f "%e %M" -o "$d/time" \
           bash "$top/scripts/mpirun.sh" "$ranks" "$exe" "$d/scene.prm" > "$d/log" 2>&1; then
        echo "$name $solver on $ranks ranks failed (see $d/log)"
        continue
      fi
      read -r seconds kb < "$d/time"
      steps=$(awk -F, -v end="$(end_time "$name")" '
        NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i; next }
        { n++; newton += $col["nonlinear_iterations"]; linear += $col["linear_iterations"]
          if (n == 1) d0 = $col["dofs"]; else { w += $col["wall_seconds"]; m++ }
          d1 = $col["dofs"]; dt = $col["dt"] }
        END { s = m > 0 ? w / m : 0
              printf "%d,%d,%d,%.2f,%.1f,%.2f,%.1f", d0, d1, n, newton / n, linear / n, s,
                     s * end / dt / 3600 }' "$d/out/statistics.csv")
      parts=",,,"
      [ "$solver" = iterative ] &&
        parts=$(/usr/bin/python3 "$top/scripts/solver-statistics.py" --run "$d/log" setup_seconds \
                patch_setup_seconds iterate_seconds patch_apply_seconds)
      echo "$name,$solver,$ranks,$steps,$seconds,$((kb / 1024)),$parts,$date,$commit" | tee -a "$csv"
    done
  done
done
