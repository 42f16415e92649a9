#!/usr/bin/env bash
# A random suspension settling in time (doc/particles.md, "A settling suspension in
# time"): the scene of benchmarks/suspension_scene.sh with N = 25 spheres in a triply
# periodic cube of edge 5 (solid fraction 0.105), 2 cells per diameter, BDF2 steps of
# Δt = 8000, each 0.044 d at Stokes' U0 = 2 Δρ g a²/(9 μ). The frozen benchmark (benchmarks/suspension_3d.sh) solves
# one configuration; here the spheres move through the periodic faces and the
# configuration evolves, as in the experiments Richardson and Zaki's (1 − φ)^4.65 fits.
# Contacts: the repulsion (Collisions/Model = repulsion) with a Range ρ of 0.1 d, well
# below the mean gap of about 0.7 d, and a force at contact K of 10 apparent weights W:
# two spheres approaching at U0 stop where the force is about W, two thirds of the range
# from touching. The contact acts at X^{n+1} = X^n + (2Δt/3) V, so over a step its
# stiffness is (2K/ρ)(2Δt/3) at most, 6 times the Stokes drag 6πμa of a sphere with
# 10 W and 60 times with the default of 100 W, which Newton resolves only in many
# iterations (doc/particles.md). The step is quasi-steady: the viscous times of the box
# and of a sphere are below 3·10⁻⁴.
#
# Writes doc/suspension_time_3d.csv (one row per step: U/U0 in the frame of zero volume
# flux, the spread of the particle velocities, how far the spheres have moved relative
# to each other, contacts, smallest gap, Newton iterations, seconds) and
# doc/suspension_time_3d.png, and prints a summary.
# Usage (regenerate):  bash benchmarks/suspension_time_3d.sh
# EXE=PATH overrides the executable, WORK=DIR the work directory (a finished run there is
# reused), NP=N the MPI ranks (1), STEPS the number of steps (103), SEED the placement (1).
# N, BOX and CELLS change the scene (25, 5, 10; doc/particles.md runs N=100 BOX=8
# CELLS=16 at the same φ and d/h, which writes doc/suspension_time_3d_n100.csv/.png);
# SOLVER=iterative uses the iterative solver without the cut-cell patch, the faster one for
# suspensions (doc/scaling.md, "Many particles"). A checkpoint every 5 steps lets a long
# run be resumed (Checkpointing/Resume = true in the written prm).
set -euo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
exe="${EXE:-$top/build/fdparticle}"
work="${WORK:-$top/benchmarks/work/suspension_time_3d}"
np="${NP:-1}"
steps="${STEPS:-103}"
seed="${SEED:-1}"
n="${N:-25}" box="${BOX:-5}" cells="${CELLS:-10}" solver="${SOLVER:-direct}" dt=8000
csv_name="suspension_time_3d"
[ "$n" = 25 ] || csv_name="suspension_time_3d_n$n"
source "$top/benchmarks/suspension_scene.sh"
mkdir -p "$work"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
name="n${n}_s${seed}_dt${dt}"
# The contact force at contact: ten apparent weights Δρ g (4/3) π a³.
stiffness=$(/usr/bin/python3 -c "import math; print(repr(10 * 4 / 3 * math.pi * 0.125))")
sections="subsection Collisions
  set Model     = repulsion
  set Range     = 0.1
  set Stiffness = $stiffness
end
subsection Checkpointing
  set Interval = 5
end
"
if [ "$solver" = iterative ]; then
  sections+="subsection Solver
  set Cut cell patch layers = -1
end
"
fi
if [ "$(tail -n +2 "$work/$name/statistics.csv" 2>/dev/null | wc -l)" -lt "$steps" ]; then
  suspension_prm "$n" "$box" "$cells" "$seed" "$solver" "$dt" $(( steps * dt )) BDF2 \
    "$work/$name" "$sections" > "$work/$name.prm"
  /usr/bin/time -f "%M" -o "$work/$name.mem" \
    bash "$top/scripts/mpirun.sh" "$np" "$exe" "$work/$name.prm" > "$work/$name.log" 2>&1
fi
/usr/bin/python3 "$top/benchmarks/suspension_time_3d.py" "$work/$name" "$box" \
  "$top/doc/$csv_name.csv"
# /usr/bin/time writes nothing when the run is stopped by hand (a long run to be resumed).
memory_kb=$(tail -n 1 "$work/$name.mem" 2>/dev/null || true)
if [[ "$memory_kb" =~ ^[0-9]+$ ]]; then
  echo "peak memory: $(( memory_kb / 1024 )) MB"
else
  echo "peak memory: not measured (the run did not end by itself)"
fi
gnuplot <<GP
set terminal pngcairo size 760,520 noenhanced
set output "$top/doc/$csv_name.png"
set datafile separator ","
set multiplot layout 2,1
set lmargin 10; set rmargin 3
set key inside right top
set xlabel "t U0 / d"
set ylabel "U / U0"
set yrange [0:1]
phi = $n * 4.0 / 3 * pi * 0.125 / $box ** 3
csv = "$top/doc/$csv_name.csv"
set title sprintf("$n random spheres settling, periodic box, phi = %.3f, d/h = %g (suspension_time_3d.sh)", phi, $cells * 1.0 / $box)
plot csv u 3:4 w l lw 2 t "U/U0, zero volume flux", (1 - phi) ** 4.65 lw 2 dt 2 t "Richardson-Zaki", \
     1 - 6.55 * phi lw 2 dt 3 t "Batchelor (1972)"
unset title
set ylabel "d, U0"
set yrange [0:1.2]
set key inside left top
plot csv u 3:7 w l lw 2 t "relative displacement / d", csv u 3:5 w l lw 2 t "sigma of vz / U0", \
     csv u 3:6 w l lw 2 t "sigma of vx, vy / U0", csv u 3:(\$9 / 0.1 < 1 ? \$9 / 0.1 : 1/0) w p pt 7 ps 0.5 t "min gap / Range (below 1: in contact)"
unset multiplot
GP
echo "wrote doc/$csv_name.csv and doc/$csv_name.png"
