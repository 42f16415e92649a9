#!/usr/bin/env bash
# Where the time of a many-particle step goes on 1 and 2 ranks (doc/scaling.md, "Two ranks
# without a patch"): the suspension of benchmarks/suspension_scene.sh (100 spheres, box 10
# on 22³ cells, 589 942 unknowns, no cut-cell patch, one Stokes step), run PAIRS times as
# a 2-rank run followed by a 1-rank one. Run it alone on the machine: a job beside it
# slows one rank count more than the other. Writes doc/strong_scaling_suspension.csv (one
# row per run: the pair, ranks, the run's wall time and peak memory of one rank, the
# TimerOutput sections of the assembly and the solve, and from the statistics line the
# preconditioner's build, the iterations, and the iterations' operator products, V-cycles
# and particle block) and doc/strong_scaling_suspension.png (each part's speedup from 1
# to 2 ranks, one bar per pair). PLOT_ONLY=1 redraws the plot from the CSV.
# Usage: bash benchmarks/strong_scaling_suspension.sh   (~7 min a pair on 2 cores, 4.3 GB)
# N, BOX, CELLS, SEED and PAIRS override the scene (100, 10, 22, 1) and the pairs (1).
set -uo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
exe="${EXE:-$top/build/fdparticle}"
work="${WORK:-$top/benchmarks/work/strong_scaling_suspension}"
n="${N:-100}" box="${BOX:-10}" cells="${CELLS:-22}" seed="${SEED:-1}" pairs="${PAIRS:-1}"
[ -x "$exe" ] || bash "$top/scripts/build.sh"
mkdir -p "$work"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
source "$top/benchmarks/suspension_scene.sh"

csv="$top/doc/strong_scaling_suspension.csv"
# The wall time of one TimerOutput section of a log ("| assemble system | 1 | 16.1s |").
section() { grep -m1 "^| $1 " "$2" | awk -F'|' '{gsub(/[ s]/, "", $4); print $4}'; }
if [ "${PLOT_ONLY:-0}" != 1 ]; then
  echo "pair,ranks,unknowns,linear_iterations,inner_iterations,wall_seconds,peak_mb,assemble_system,assemble_residual,solve,build,iterations,operator_products,velocity_cycles,multiplier_cycles,particle_block" > "$csv"
  for pair in $(seq 1 "$pairs"); do
    for ranks in 2 1; do
      d="$work/pair$pair-ranks$ranks"
      suspension_prm "$n" "$box" "$cells" "$seed" iterative 1 1 BDF1 "$d/out" "subsection Solver
  set Cut cell patch layers = -1
  set Iterative solver statistics = true
end
" > "$d.prm"
      if ! /usr/bin/time -f "%e %M" -o "$d.time" \
           bash "$top/scripts/mpirun.sh" "$ranks" "$exe" "$d.prm" > "$d.log" 2>&1; then
        echo "pair $pair on $ranks ranks failed (see $d.log)"
        continue
      fi
      read -r wall kb < "$d.time"
      parts=$(/usr/bin/python3 "$top/scripts/solver-statistics.py" "$d.log" setup_seconds \
        iterate_seconds product_seconds velocity_cycle_seconds multiplier_cycle_seconds \
        particle_block_seconds)
      echo "$pair,$ranks,$(bash "$top/scripts/statistics-columns.sh" "$d/out/statistics.csv" last dofs linear_iterations inner_iterations),$wall,$((kb / 1024)),$(section 'assemble system' "$d.log"),$(section 'assemble residual' "$d.log"),$(section solve "$d.log"),$parts" | tee -a "$csv"
    done
  done
fi

# Speedups per part and pair: the 1-rank value over the 2-rank one.
/usr/bin/python3 - "$csv" "$work/speedups.dat" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
parts = ["wall_seconds", "assemble_system", "assemble_residual", "build", "iterations",
         "operator_products", "velocity_cycles", "multiplier_cycles", "particle_block"]
pairs = sorted({r["pair"] for r in rows})
with open(sys.argv[2], "w") as out:
    out.write("part " + " ".join("pair" + p for p in pairs) + "\n")
    for part in parts:
        values = []
        for p in pairs:
            by = {r["ranks"]: float(r[part]) for r in rows if r["pair"] == p}
            values.append(by["1"] / by["2"] if "1" in by and "2" in by else float("nan"))
        out.write(part.replace("_seconds", "").replace("_", "-") + " "
                  + " ".join("%.3f" % v for v in values) + "\n")
PY
gnuplot <<GNUPLOT
set terminal pngcairo size 900,480 noenhanced
set output "$top/doc/strong_scaling_suspension.png"
set title "Speedup 1 -> 2 ranks by part: $n spheres, box $box on $cells^3 cells (benchmarks/strong_scaling_suspension.sh)"
set style data histograms
set style histogram clustered gap 1
set style fill solid 0.6 border -1
set ylabel "time on 1 rank / time on 2 ranks"
set yrange [0:2.6]
set xtics rotate by -30
set grid ytics
set key top right
plot for [i=2:*] "$work/speedups.dat" using i:xtic(1) title columnheader(i), 1.6 with lines dashtype 2 title "target 1.6"
GNUPLOT
