#!/usr/bin/env bash
# The cut-cell patch of a Navier-Stokes Jacobian factored as LU or as LDLT of its symmetric
# part (Solver/Cut cell patch symmetric part; doc/scaling.md, "The patch at its limits"):
#   cavity   prm/cavity.prm with level-set cut cells and 2 particle refinement levels
#            (the adaptive 3D cavity of doc/smoothness.md), two steps
#   tencate  prm/validation/tencate.prm at ten Cate's E4 (rho_f = 960, mu = 0.058, Re 32
#            at the end), to t = END_TENCATE (default 0.2, 20 steps)
# both with the iterative solver on one rank. Writes doc/patch_symmetric_part.csv: one row
# per run with the steps, Newton and FGMRES iterations over the run, the largest factor
# memory of a patch that was not symmetric, the peak resident memory, the run's wall
# time, the date and the commit.
# Usage: [END_TENCATE=0.2] bash benchmarks/patch_symmetric_part.sh
#        (~15 min on 2 cores; alone on the machine)
set -uo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
exe="${EXE:-$top/build/fdparticle}"
work="${WORK:-$top/benchmarks/work/patch_symmetric_part}"
end_tencate="${END_TENCATE:-0.2}"
[ -x "$exe" ] || bash "$top/scripts/build.sh"
mkdir -p "$work"
. "$top/benchmarks/scaling_scenes.sh"
csv="$top/doc/patch_symmetric_part.csv"
date=$(date -u +%Y-%m-%d); commit=$(git -C "$top" rev-parse --short HEAD)

scene() { # name directory symmetric_part -> prm on stdout
  case $1 in
    cavity)
      sed -e "s#^\(\s*set Directory\s*=\).*#\1 $2#" -e "s/^\(\s*set End time\s*=\).*/\1 0.02/" \
          -e "s/^\(\s*set VTU interval\s*=\).*/\1 0/" "$top/prm/cavity.prm"
      adaptive_levelset ;;
    tencate)
      sed -e "s#^\(\s*set Directory\s*=\).*#\1 $2#" -e "s/^\(\s*set End time\s*=\).*/\1 $end_tencate/" \
          -e "s/^\(\s*set Viscosity\s*=\).*/\1 0.058/" -e "s/^\(\s*set Density\s*=\).*/\1 960/" \
          "$top/prm/validation/tencate.prm" ;;
  esac
  printf 'subsection Solver\n  set Linear solver = iterative\n  set Iterative solver statistics = true\n  set Cut cell patch symmetric part = %s\nend\n' "$3"
}

echo "scene,symmetric_part,steps,newton_iterations,linear_iterations,nonsymmetric_patch_mb,peak_mb,run_seconds,date,commit" > "$csv"
for name in cavity tencate; do
  for symmetric_part in false true; do
    d="$work/$name-$symmetric_part"
    rm -rf "$d"; mkdir -p "$d"
    scene "$name" "$d/out" "$symmetric_part" > "$d/scene.prm"
    if ! /usr/bin/time -f "%e %M" -o "$d/time" bash "$top/scripts/mpirun.sh" 1 "$exe" "$d/scene.prm" > "$d/log" 2>&1; then
      echo "$name $symmetric_part failed (see $d/log)"
      continue
    fi
    read -r seconds kb < "$d/time"
    sums=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i; next }
                    { n++; newton += $col["nonlinear_iterations"]; linear += $col["linear_iterations"] }
                    END { print n "," newton "," linear }' "$d/out/statistics.csv")
    # The patches that were not symmetric: "factored in N MB (largest rank)" or "(largest
    # rank, symmetric part)".
    mb=$(grep -o 'factored in [0-9.]* MB (largest rank[^)]*)' "$d/log" | grep -v ', symmetric)' |
         awk '{ if ($3 > m) m = $3 } END { print m + 0 }')
    echo "$name,$symmetric_part,$sums,$mb,$((kb / 1024)),$seconds,$date,$commit" | tee -a "$csv"
  done
done
