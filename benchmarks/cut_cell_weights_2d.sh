#!/usr/bin/env bash
# Load balance of the cut cells (doc/particles.md), on RANKS ranks (default 2), two scenes:
#  - settling: 64 disks (radius 0.04, density 1.1) placed at random in the bottom 30 % of
#    a closed 2 x 2 box, base mesh 32 x 32 refined one level around the disks (the
#    partition is redone at every refinement), Collisions/Model = repulsion, 4 steps of
#    0.005, for Quadrature/Cut cell cost = 1 (equal cell counts), 2, 4 and 8;
#  - carried: 128 disks (radius 0.04) in eight rows in the bottom half of the same box,
#    carried up by 0.4 at a prescribed velocity in 10 Stokes steps, on 64 x 64 cells
#    never refined (the partition follows the disks only by rebalancing), for cost 1 and 4
#    (CARRIED_COSTS; "1 4 1 4 1 4" repeats each three times).
# Writes doc/cut_cell_weights_2d.csv: per scene and cost, the cells of the smallest and
# the largest rank at the start, seconds per step, the assembly seconds per step
# (TimerOutput, rank 0's wall clock; the ranks wait for each other in the solve) and the
# repartitions during the steps; and the plot doc/cut_cell_weights_2d.png (settling).
#
# Usage (regenerate):  bash benchmarks/cut_cell_weights_2d.sh
# EXE=PATH overrides the executable, WORK=DIR the work directory, COSTS="1 4" the costs.
set -euo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
exe="${EXE:-$top/build/fdparticle}"
work="${WORK:-$top/benchmarks/work/cut_cell_weights_2d}"
ranks="${RANKS:-2}"
source "$top/benchmarks/settling_disks_scene.sh"
mkdir -p "$work"
csv="$top/doc/cut_cell_weights_2d.csv"
echo "scene,cut_cell_cost,ranks,min_cells,max_cells,seconds_per_step,assembly_seconds_per_step,repartitions" > "$csv"

settling() { # cost
  settling_disks_prm 64 32 0.6
  cat <<PRM
subsection Quadrature
  set Cut cells = level set
  set Cut cell cost = $1
end
subsection Refinement
  set Particle refinement levels = 1
end
PRM
}

carried() { # cost
  awk 'BEGIN { for (row = 0; row < 8; ++row) for (column = 0; column < 16; ++column)
                printf "%g, %g, 0.04, 1, prescribed, 0, 2\n", 0.0625 + 0.125 * column, 0.1 + 0.125 * row }' \
    > "$work/carried.csv"
  cat <<PRM
set Dimension = 2
set Gravity = 0, 0
subsection Geometry
  set Lower corner = 0, 0
  set Upper corner = 2, 2
  set Subdivisions = 64, 64
end
subsection Fluid
  set Convection = false
end
subsection Particles
  set Particle file = $work/carried.csv
end
subsection Quadrature
  set Cut cells = level set
  set Cut cell cost = $1
end
subsection Time
  set End time = 0.2
  set Time step = 0.02
end
PRM
}

for scene in settling carried; do
  costs="${COSTS:-1 2 4 8}"
  [ "$scene" = carried ] && costs="${CARRIED_COSTS:-1 4}"
  for cost in $costs; do
    run="$scene-c$cost"
    { "$scene" "$cost"
      printf 'subsection Output\n  set Directory = %s\n  set VTU interval = 0\nend\n' "$work/$run"
    } > "$work/$run.prm"
    bash "$top/scripts/mpirun.sh" "$ranks" "$exe" "$work/$run.prm" > "$work/$run.log"
    /usr/bin/python3 - "$work" "$run" "$scene" "$cost" "$ranks" >> "$csv" <<'PY'
import csv, re, sys
work, run, scene, cost, ranks = sys.argv[1:6]
log = open(f"{work}/{run}.log").read()
cells = re.search(r"\((\d+)-(\d+) cells each\)", log)
lo, hi = cells.groups() if cells else ("", "")
def section(name):
    m = re.search(r"\|\s*" + name + r"\s*\|\s*\d+\s*\|\s*([0-9.]+)(m?s)", log)
    return float(m.group(1)) / (1000 if m.group(2) == "ms" else 1) if m else 0.0
rows = list(csv.DictReader(open(f"{work}/{run}/statistics.csv")))
steps = len(rows)
seconds = sum(float(r["wall_seconds"]) for r in rows) / steps
assembly = (section("assemble residual") + section("assemble system")) / steps
print(f"{scene},{cost},{ranks},{lo},{hi},{seconds:.3f},{assembly:.3f},{log.count('partition rebalanced')}")
PY
    tail -1 "$csv"
  done
done

gnuplot <<GNUPLOT
set terminal pngcairo size 700,450
set output "$top/doc/cut_cell_weights_2d.png"
set datafile separator ","
set logscale x 2
set xlabel "Quadrature/Cut cell cost"
set ylabel "seconds per step"
set yrange [0:*]
set key bottom right
plot "< grep ^settling $csv" using 2:6 with linespoints title "whole step", \
     "< grep ^settling $csv" using 2:7 with linespoints title "assembly (rank 0)"
GNUPLOT
