#!/usr/bin/env bash
# Load balance of the cut cells (doc/particles.md): 64 disks (radius 0.04, density 1.1)
# placed at random in the bottom 30 % of a closed 2 x 2 box, base mesh 32 x 32 refined one
# level around the disks, level-set cut cells, Collisions/Model = repulsion, 4 steps of
# 0.005, on RANKS ranks (default 2), for Quadrature/Cut cell cost = 1 (equal cell counts),
# 2, 4 and 8. Writes doc/cut_cell_weights_2d.csv: per cost, the cells of the smallest and
# the largest rank, seconds per step, and the assembly seconds per step (TimerOutput,
# rank 0's wall clock; the ranks wait for each other in the solve), and the plot
# doc/cut_cell_weights_2d.png.
#
# Usage (regenerate):  bash benchmarks/cut_cell_weights_2d.sh
# EXE=PATH overrides the executable, WORK=DIR the work directory, COSTS="1 4" the costs.
set -euo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
exe="${EXE:-$top/build/fdparticle}"
work="${WORK:-$top/benchmarks/work/cut_cell_weights_2d}"
ranks="${RANKS:-2}"
mkdir -p "$work"
export OMPI_MCA_mpi_yield_when_idle=1
csv="$top/doc/cut_cell_weights_2d.csv"
echo "cut_cell_cost,ranks,min_cells,max_cells,seconds_per_step,assembly_seconds_per_step" > "$csv"
for cost in ${COSTS:-1 2 4 8}; do
  cat > "$work/c$cost.prm" <<PRM
set Dimension = 2
set Gravity = 0, -981
subsection Geometry
  set Lower corner = 0, 0
  set Upper corner = 2, 2
  set Subdivisions = 32, 32
end
subsection Fluid
  set Density = 1
  set Viscosity = 0.1
end
subsection Particles
  subsection Random particles
    set Count = 64
    set Radius = 0.04
    set Density = 1.1
    set Minimum gap = 0.02
    set Seed = 1
    set Lower corner = 0, 0
    set Upper corner = 2, 0.6
  end
end
subsection Quadrature
  set Cut cells = level set
  set Cut cell cost = $cost
end
subsection Refinement
  set Particle refinement levels = 1
end
subsection Collisions
  set Model = repulsion
end
subsection Time
  set End time = 0.02
  set Time step = 0.005
end
subsection Output
  set Directory = $work/c$cost
  set VTU interval = 0
end
PRM
  mpirun --oversubscribe -np "$ranks" "$exe" "$work/c$cost.prm" > "$work/c$cost.log"
  /usr/bin/python3 - "$work" "$cost" "$ranks" >> "$csv" <<'PY'
import csv, re, sys
work, cost, ranks = sys.argv[1:4]
log = open(f"{work}/c{cost}.log").read()
cells = re.search(r"\((\d+)-(\d+) cells each\)", log)
lo, hi = cells.groups() if cells else ("", "")
def section(name):
    m = re.search(r"\|\s*" + name + r"\s*\|\s*\d+\s*\|\s*([0-9.]+)(m?s)", log)
    return float(m.group(1)) / (1000 if m.group(2) == "ms" else 1) if m else 0.0
rows = list(csv.DictReader(open(f"{work}/c{cost}/statistics.csv")))
steps = len(rows)
seconds = sum(float(r["wall_seconds"]) for r in rows) / steps
assembly = (section("assemble residual") + section("assemble system")) / steps
print(f"{cost},{ranks},{lo},{hi},{seconds:.3f},{assembly:.3f}")
PY
  tail -1 "$csv"
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
plot "$csv" every ::1 using 1:5 with linespoints title "whole step", \
     "$csv" every ::1 using 1:6 with linespoints title "assembly (rank 0)"
GNUPLOT
