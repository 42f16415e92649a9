#!/usr/bin/env bash
# Work per time step against the number of particles at a fixed 3D mesh (doc/particles.md):
# N = 1, 10, 100 spheres (radius 1/12, two cells per diameter, density 1.2) placed at
# random in a closed 1 x 1 x 1.5 box of fluid (solid fraction 0.16 at N = 100) on a uniform
# 12 x 12 x 18 mesh (no particle refinement, so every N has the same mesh, about 150 000
# unknowns), Collisions/Model = repulsion, 2 steps of 0.01, with the direct and the
# iterative linear solver. Writes
# doc/particle_count_3d.csv (per solver and N: particle unknowns, seconds per step, in
# assembly and in the linear solve, linear iterations, peak memory) and the plot
# doc/particle_count_3d.png.
#
# Usage (regenerate):  bash benchmarks/particle_count_3d.sh
# EXE=PATH overrides the executable, WORK=DIR the work directory, COUNTS="1 10" the N,
# SOLVERS="iterative" the linear solvers.
set -euo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
exe="${EXE:-$top/build/fdparticle}"
work="${WORK:-$top/benchmarks/work/particle_count_3d}"
mkdir -p "$work"
csv="$top/doc/particle_count_3d.csv"
echo "solver,particles,particle_unknowns,dofs,steps,newton_iterations_per_step,linear_iterations_per_step,seconds_per_step,assembly_seconds_per_step,solve_seconds_per_step,peak_MB" > "$csv"
for solver in ${SOLVERS:-direct iterative}; do
  for n in ${COUNTS:-1 10 100}; do
    name="${solver}_n$n"
    cat > "$work/$name.prm" <<PRM
set Dimension = 3
set Gravity = 0, 0, -10
subsection Geometry
  set Lower corner = 0, 0, 0
  set Upper corner = 1, 1, 1.5
  set Subdivisions = 12, 12, 18
end
subsection Fluid
  set Density = 1
  set Viscosity = 0.01
end
subsection Particles
  subsection Random particles
    set Count = $n
    set Radius = 0.0833333
    set Density = 1.2
    set Minimum gap = 0.02
    set Seed = 1
  end
end
subsection Collisions
  set Model = repulsion
end
subsection Quadrature
  set Cut cells = level set
end
subsection Solver
  set Linear solver = $solver
end
subsection Time
  set End time = 0.02
  set Time step = 0.01
end
subsection Output
  set Directory = $work/$name
  set VTU interval = 0
end
PRM
    /usr/bin/time -f "%M" -o "$work/$name.mem" "$exe" "$work/$name.prm" > "$work/$name.log"
    /usr/bin/python3 "$top/benchmarks/particle_count_row.py" "$work" "$name" "$solver,$n" --linear >> "$csv"
    tail -1 "$csv"
  done
done
gnuplot <<GP
set terminal pngcairo size 760,480 noenhanced
set output "$top/doc/particle_count_3d.png"
set datafile separator ","
set logscale x 10; set xrange [0.8:130]; set logscale y; set yrange [*:*]
set xlabel "spheres (fixed 12 x 12 x 18 mesh, about 150 000 unknowns)"; set ylabel "seconds per step"
set key top left
set title "Work per step against particle count in 3D (benchmarks/particle_count_3d.sh)"
plot "< grep ^direct $csv" u 2:8 w lp lw 2 t "direct: step", \
     "" u 2:10 w lp lw 2 dt 2 t "direct: linear solve", \
     "< grep ^iterative $csv" u 2:8 w lp lw 2 t "iterative: step", \
     "" u 2:10 w lp lw 2 dt 2 t "iterative: linear solve", \
     "< grep ^iterative $csv" u 2:9 w lp lw 2 dt 3 t "assembly (iterative runs)"
GP
echo "wrote doc/particle_count_3d.csv and doc/particle_count_3d.png"
