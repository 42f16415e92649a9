#!/usr/bin/env bash
# Strong scaling of the iterative solver (doc/scaling.md, "The patch on all ranks"): the 3D
# sediment step of benchmarks/scaling_scenes.sh at growing n on 1 and 2 ranks, with
# `Iterative solver statistics` for the parts of the solve. Writes doc/strong_scaling.csv
# (one row per run: unknowns, FGMRES and inner iterations, the step's wall time, the
# run's wall time and peak memory of one rank, and from the statistics line the setup of
# the preconditioner, its patch's part, the iterations and the patch's part of those, the
# date and the commit) and
# doc/strong_scaling.png (step time against unknowns, both rank counts). Compare within
# one run (the machine is shared). PLOT_ONLY=1 redraws the plot from the CSV.
# Usage: bash benchmarks/strong_scaling.sh   (~8 min on 2 cores, 24 GB, with SIZES="12 16 21 24";
# 9 GB on one rank at n = 24)
set -uo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
exe="${EXE:-$top/build/fdparticle}"
work="${WORK:-$top/benchmarks/work/strong_scaling}"
sizes="${SIZES:-12 16 21 24}"
[ -x "$exe" ] || bash "$top/scripts/build.sh"
mkdir -p "$work"
. "$top/benchmarks/scaling_scenes.sh"

csv="$top/doc/strong_scaling.csv"
if [ "${PLOT_ONLY:-0}" != 1 ]; then
echo "n,ranks,dofs,linear_iterations,inner_iterations,step_seconds,wall_seconds,peak_mb,setup_seconds,patch_setup_seconds,iterate_seconds,patch_apply_seconds,date,commit" > "$csv"
commit=$(git -C "$top" rev-parse --short HEAD 2>/dev/null || echo unknown)
for n in $sizes; do
  for ranks in 1 2; do
    d="$work/sediment-$n-$ranks"
    mkdir -p "$d"
    { sediment "$n"
      printf 'subsection Solver\n  set Linear solver = iterative\n'
      printf '  set Iterative solver statistics = true\nend\n'
      printf 'subsection Output\n  set Directory = %s\n  set VTU interval = 0\nend\n' "$d/out"
    } > "$d/scene.prm"
    if ! /usr/bin/time -f "%e %M" -o "$d/time" \
         bash "$top/scripts/mpirun.sh" "$ranks" "$exe" "$d/scene.prm" > "$d/log" 2>&1; then
      echo "sediment $n on $ranks ranks failed (see $d/log)"
      continue
    fi
    read -r wall kb < "$d/time"
    parts=$(/usr/bin/python3 "$top/scripts/solver-statistics.py" "$d/log" setup_seconds \
      patch_setup_seconds iterate_seconds patch_apply_seconds)
    echo "$n,$ranks,$(bash "$top/scripts/statistics-columns.sh" "$d/out/statistics.csv" last dofs linear_iterations inner_iterations wall_seconds),$wall,$((kb / 1024)),$parts,$(date -u +%F),$commit" | tee -a "$csv"
  done
done
fi

gnuplot <<GNUPLOT
set terminal pngcairo size 800,500
set output "$top/doc/strong_scaling.png"
set datafile separator ","
set logscale xy
set xlabel "finite-element unknowns"
set ylabel "wall time of the step [s]"
set key top left
plot for [r in "1 2"] sprintf("< grep -E '^[0-9]+,%s,' $csv", r) using 3:6 with linespoints title r." rank(s)", \
  for [r in "1 2"] sprintf("< grep -E '^[0-9]+,%s,' $csv", r) using 3:(\$10+\$12) with linespoints dashtype 2 title r." rank(s): the patch's part"
GNUPLOT
