#!/usr/bin/env bash
# Direct against iterative linear solver (doc/scaling.md): wall time, peak memory and
# linear iterations of one Stokes step, on two 3D scenes at growing mesh size
# (benchmarks/scaling_scenes.sh):
#  - sediment: the seed's sediment scene (box 1 x 2 x 1, sphere R = 0.2, rho_P = 1.5,
#    mu = 1), Subdivisions n x 2n x n, one BDF1 step of 0.1;
#  - array:    prm/validation/array3d.prm (a fixed sphere in a periodic cube, c = 0.064,
#    dt = 100: steady Stokes), Subdivisions n x n x n, no particle refinement.
# Each run is one process on RANKS ranks (default 1); compare the ratios within one run of
# the script (the machine is shared). Writes doc/scaling.csv, doc/scaling_time.png,
# doc/scaling_memory.png and doc/scaling_iterations.png (FGMRES iterations against mesh
# size); each row ends with the date and the commit it was measured at. Solvers: direct,
# iterative (the defaults: the cut-cell patch and the cheap iterations first) and
# iterative-inner (no patch, always the inner solve: Cut cell patch layers = -1, Cheap
# iterations = 0); SOLVERS="iterative" runs only that one.
# PLOT_ONLY=1 redraws the plots from doc/scaling.csv.
# Usage: bash benchmarks/scaling.sh     (~10 min on 2 cores with the default SIZES="4 6 8")
set -uo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
exe="${EXE:-$top/build/fdparticle}"
work="${WORK:-$top/benchmarks/work/scaling}"
sizes="${SIZES:-4 6 8}"
ranks="${RANKS:-1}"
solvers="${SOLVERS:-direct iterative iterative-inner}"
[ -x "$exe" ] || bash "$top/scripts/build.sh"
mkdir -p "$work"

. "$top/benchmarks/scaling_scenes.sh"

csv="$top/doc/scaling.csv"
if [ "${PLOT_ONLY:-0}" != 1 ]; then
echo "scene,n,solver,dofs,linear_iterations,inner_iterations,wall_seconds,peak_mb,date,commit" > "$csv"
commit=$(git -C "$top" rev-parse --short HEAD 2>/dev/null || echo unknown)
for name in sediment array; do
  for n in $sizes; do
    for solver in $solvers; do
      d="$work/$name-$n-$solver"
      mkdir -p "$d"
      { "$name" "$n"
        printf 'subsection Solver\n  set Linear solver = %s\n' "${solver%-inner}"
        [ "$solver" = iterative-inner ] &&
          printf '  set Cut cell patch layers = -1\n  set Cheap iterations = 0\n'
        printf 'end\n'
        printf 'subsection Output\n  set Directory = %s\n  set VTU interval = 0\nend\n' "$d/out"
      } > "$d/scene.prm"
      cmd=("$exe" "$d/scene.prm")
      [ "$ranks" -gt 1 ] && cmd=(bash "$top/scripts/mpirun.sh" "$ranks" "${cmd[@]}")
      if ! /usr/bin/time -f "%e %M" -o "$d/time" "${cmd[@]}" > "$d/log" 2>&1; then
        echo "$name $n $solver failed (see $d/log)"
        continue
      fi
      read -r wall kb < "$d/time"
      echo "$name,$n,$solver,$(bash "$top/scripts/statistics-columns.sh" "$d/out/statistics.csv" last dofs linear_iterations inner_iterations),$wall,$((kb / 1024)),$(date -u +%F),$commit" |
        tee -a "$csv"
    done
  done
done
fi

for what in time memory; do
  col=7 label="wall time of the run [s]"
  [ "$what" = memory ] && col=8 label="peak memory of one rank [MB]"
  gnuplot <<GNUPLOT
set terminal pngcairo size 800,500
set output "$top/doc/scaling_$what.png"
set datafile separator ","
set logscale xy
set xlabel "finite-element unknowns"
set ylabel "$label"
set key top left
plot for [s in "sediment array"] for [v in "direct iterative iterative-inner"] \
  sprintf("< grep '^%s,[0-9]*,%s,' $csv", s, v) using 4:$col with linespoints title s." ".v
GNUPLOT
done

gnuplot <<GNUPLOT
set terminal pngcairo size 800,500
set output "$top/doc/scaling_iterations.png"
set datafile separator ","
set logscale x
set xlabel "finite-element unknowns"
set ylabel "iterations of the step"
set key top left
plot for [s in "sediment array"] for [v in "iterative iterative-inner"] \
  sprintf("< grep '^%s,[0-9]*,%s,' $csv", s, v) using 4:5 with linespoints title s." ".v." FGMRES", \
  for [s in "sediment array"] for [v in "iterative iterative-inner"] \
  sprintf("< grep '^%s,[0-9]*,%s,' $csv", s, v) using 4:(\$6/10) with linespoints dashtype 2 title s." ".v." inner / 10"
GNUPLOT
