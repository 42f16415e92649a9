#!/usr/bin/env bash
# Work per time step against the number of particles at a fixed mesh (doc/particles.md):
# N = 1, 4, 16, 64, 128 disks (radius 0.04, density 1.1) placed at random in a closed 2 x 2
# box of fluid on a uniform 64 x 64 mesh (no particle refinement, so every N has the same
# mesh), Collisions/Model = repulsion, 4 steps of 0.005. Writes doc/particle_count_2d.csv
# (per N: particle unknowns, seconds per step, in assembly and in the linear solve, peak
# memory) and the plot doc/particle_count_2d.png.
#
# Usage (regenerate):  bash benchmarks/particle_count_2d.sh
# EXE=PATH overrides the executable, WORK=DIR the work directory, COUNTS="1 4" the N.
set -euo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
exe="${EXE:-$top/build/fdparticle}"
work="${WORK:-$top/benchmarks/work/particle_count_2d}"
source "$top/benchmarks/settling_disks_scene.sh"
mkdir -p "$work"
csv="$top/doc/particle_count_2d.csv"
echo "particles,particle_unknowns,dofs,steps,newton_iterations_per_step,seconds_per_step,assembly_seconds_per_step,solve_seconds_per_step,peak_MB" > "$csv"
for n in ${COUNTS:-1 4 16 64 128}; do
  { settling_disks_prm "$n" 64
    printf 'subsection Output\n  set Directory = %s\n  set VTU interval = 0\nend\n' "$work/n$n"
  } > "$work/n$n.prm"
  /usr/bin/time -f "%M" -o "$work/n$n.mem" "$exe" "$work/n$n.prm" > "$work/n$n.log"
  /usr/bin/python3 "$top/benchmarks/particle_count_row.py" "$work" "n$n" "$n" >> "$csv"
  tail -1 "$csv"
done
gnuplot <<GP
set terminal pngcairo size 760,480 noenhanced
set output "$top/doc/particle_count_2d.png"
set datafile separator ","
set logscale x 2; set xrange [0.8:160]; set yrange [0:*]
set xlabel "particles (fixed 64 x 64 mesh)"; set ylabel "seconds per step"; set key top left
set y2label "peak memory [MB]"; set y2range [0:*]; set ytics nomirror; set y2tics
set title "Work per step against particle count (benchmarks/particle_count_2d.sh)"
plot "$csv" u 1:6 every ::1 w lp lw 2 t "step", "" u 1:8 every ::1 w lp lw 2 t "linear solve", \
     "" u 1:7 every ::1 w lp lw 2 t "assembly", "" u 1:9 every ::1 axes x1y2 w lp lw 2 dt 2 t "peak memory (right)"
GP
echo "wrote doc/particle_count_2d.csv and doc/particle_count_2d.png"
