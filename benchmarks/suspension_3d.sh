#!/usr/bin/env bash
# Hindered settling of a random suspension of spheres in a periodic box (doc/particles.md,
# "A settling suspension"): N = 100 equal spheres (radius 0.5) placed at random (minimum
# gap d/4) in a triply periodic cube, Stokes flow, one quasi-steady step. The settling
# velocity of the frozen configuration, U = mean particle velocity − mean velocity of the
# box (the frame of zero volume flux), against Stokes' U0 = 2 Δρ g a² / (9 μ), at solid
# fractions 0.052 (box 10) and 0.102 (box 8) at 2 cells per diameter, 0.102 also at 3.
# Each configuration is frozen (one step): one sample of a well-mixed suspension (three
# seeds at d/h = 2). The centres fill the whole box, the spheres crossing its periodic
# faces (doc/method.md §12); the rows measured before that, with gaps at the faces, are
# kept in doc/suspension_3d_gaps.csv and .png. The mesh: one configuration of 25 spheres
# at 2, 3 and 4 cells per diameter. Suspensions run without the cut-cell patch
# (Cut cell patch layers = -1; the same U/U0, in less time at two cells per diameter and
# less memory at all: doc/scaling.md).
# Each box and mesh is also run with one sphere (four random places at d/h = 2, two at 3),
# whose exact U/U0 is the Sangani–Acrivos series for a simple cubic array
# (doc/references/README.md): measured over exact is the discretization's factor, by
# which the suspension's U/U0 is also given corrected. The box's size: at a solid fraction
# of 0.10–0.105, 25, 100 and 200 spheres (boxes 5, 8, 10; d/h = 2). A periodic box of N
# spheres is a lattice of N-sphere cells, whose leading effect on U/U0 goes like
# (φ/N)^{1/3}, as Hasimoto's term for one sphere. The placement: the same 100-sphere
# boxes, and 25 spheres (seed 1) at 2 and 4 cells per diameter, with a minimum gap of d/50
# instead of d/4 (nearly the uniform pair distribution down to contact that Batchelor
# averages over; the closest gaps are then below a cell).
#
# Scene: μ = 10⁴, ρ_f = 1, ρ_s = 2, g = 1, Δt = 1 (BDF1). The viscous time of the box,
# ρ_f L²/(4π² μ) < 3e-4, and of a sphere, ρ_s a²/μ = 5e-5, are far below Δt, so the one
# step is the Stokes solution of the configuration; the spheres move 6e-6 in it (the scene:
# benchmarks/suspension_scene.sh).
#
# Writes doc/suspension_3d.csv (one row per run: time of the step, peak memory of the
# largest rank) and doc/suspension_3d.png.
# Usage (regenerate):  bash benchmarks/suspension_3d.sh
# EXE=PATH overrides the executable, WORK=DIR the work directory (finished runs there are
# reused), NP=N the MPI ranks (1), CASES the runs ("N L cells seed [gap]" separated by ';';
# gap: the placement's minimum gap, default d/4).
set -euo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
exe="${EXE:-$top/build/fdparticle}"
work="${WORK:-$top/benchmarks/work/suspension_3d}"
np="${NP:-1}"
default_cases="100 8 16 1;100 8 16 2;100 8 16 3;1 8 16 1;1 8 16 2;1 8 16 3;1 8 16 4;\
100 8 16 1 0.02;100 8 16 2 0.02;100 8 16 3 0.02;\
100 10 20 1;100 10 20 2;100 10 20 3;1 10 20 1;1 10 20 2;1 10 20 3;1 10 20 4;\
100 10 20 1 0.02;100 10 20 2 0.02;100 10 20 3 0.02;\
25 5 10 1;25 5 10 2;25 5 10 3;25 5 10 4;25 5 10 5;25 5 10 6;\
1 5 10 1;1 5 10 2;1 5 10 3;1 5 10 4;200 10 20 1;200 10 20 2;\
100 8 24 1;1 8 24 1;1 8 24 2;25 5 15 1;1 5 15 1;25 5 20 1;1 5 20 1;25 5 10 1 0.02;25 5 20 1 0.02"
source "$top/benchmarks/suspension_scene.sh"
mkdir -p "$work"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
IFS=';' read -ra cases <<< "${CASES:-$default_cases}"
for case in "${cases[@]}"; do
  read -r n box cells seed gap <<< "$case"
  name="n${n}_L${box}_c${cells}_s${seed}${gap:+_g$gap}"
  [ -s "$work/$name/statistics.csv" ] && continue
  # Many spheres: no cut-cell patch (doc/scaling.md, "Many particles"); one: the default.
  sections=""
  [ "$n" -gt 1 ] && sections="subsection Solver
  set Cut cell patch layers = -1
end
"
  suspension_prm "$n" "$box" "$cells" "$seed" iterative 1 1 BDF1 "$work/$name" "$sections" \
    "$gap" > "$work/$name.prm"
  echo "$np" > "$work/$name.ranks"
  /usr/bin/time -f "%M" -o "$work/$name.mem" \
    bash "$top/scripts/mpirun.sh" "$np" "$exe" "$work/$name.prm" > "$work/$name.log" 2>&1 ||
    { echo "$name stopped: $(grep -m1 -i 'error' "$work/$name.log")"; continue; }
  echo "$name: $(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
    { r = $c["dofs"] "," $c["linear_iterations"] "," $c["wall_seconds"] } END { print r }' \
    "$work/$name/statistics.csv") (unknowns, FGMRES, s)"
done
/usr/bin/python3 "$top/benchmarks/suspension_3d.py" "$work" "$top/doc/suspension_3d.csv"
gnuplot <<GP
set terminal pngcairo size 760,480 noenhanced
set output "$top/doc/suspension_3d.png"
set datafile separator ","
set xlabel "solid fraction"; set ylabel "U / U0, discretization factor removed"
set xrange [0:0.12]; set yrange [0:1]
set key bottom left
set title "Settling velocity of random spheres, periodic box (benchmarks/suspension_3d.sh)"
rz(x) = (1 - x) ** 4.65
csv = "$top/doc/suspension_3d.csv"
# Columns: 1 particles, 4 solid fraction, 5 cells per diameter, 9 U/U0, 10 corrected,
# 15 minimum gap.
pick(n, dh, col) = (column(1) == n && abs(column(5) - dh) < 0.01 && column(15) == 0.25) ? column(col) : 1/0
close(col) = (column(1) == 100 && column(15) < 0.25) ? column(col) : 1/0
plot rz(x) lw 2 t "Richardson-Zaki, n = 4.65", 1 - 6.55 * x lw 2 dt 2 t "Batchelor (1972), 1 - 6.55 phi", \
     csv u 4:(pick(100, 2, 10)) w p pt 7 ps 1.5 t "100 spheres, d/h = 2", \
     csv u 4:(pick(25, 2, 10)) w p pt 5 ps 1.5 t "25 spheres, d/h = 2", \
     csv u 4:(pick(25, 3, 10)) w p pt 9 ps 1.5 t "25 spheres, d/h = 3", \
     csv u 4:(pick(25, 4, 10)) w p pt 11 ps 1.5 t "25 spheres, d/h = 4", \
     csv u 4:(pick(200, 2, 10)) w p pt 13 ps 1.5 t "200 spheres, d/h = 2", \
     csv u 4:(close(10)) w p pt 6 ps 1.5 t "100 spheres, d/h = 2, gap d/50"
GP
echo "wrote doc/suspension_3d.csv and doc/suspension_3d.png"
