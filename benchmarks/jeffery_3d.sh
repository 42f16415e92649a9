#!/usr/bin/env bash
# Jeffery's orbit of a prolate spheroid in 3D (doc/shapes.md): a neutrally buoyant
# spheroid, semi-axes 0.2 x 0.1 x 0.1, its axis at 45 degrees between the flow x and the
# vorticity axis z, in the simple shear between walls y = +-1 moving at +-1 (G = 1),
# periodic in x and z, Stokes (no convection, G a^2 rho/mu = 0.04), level-set cut cells,
# LEVELS particle levels on a 6^3 base mesh (default 3: b/h = 2.4; 4: b/h = 4.8),
# dt = 0.1 to t = END_TIME
# (default 9: half of the Jeffery period 2 pi (r + 1/r)/G = 15.7 after the shear has
# developed at t = 1, the azimuth turning by pi), iterative solver, one rank.
# benchmarks/jeffery_orbit_3d.py compares the axis from t = 1 on with Jeffery's equation
# integrated from the simulated axis at t = 1: the time to turn, the largest angle between
# the two axes and the drift of the orbit constant C.
# Writes its row of doc/shapes_jeffery_3d.csv (one row per b/h, with the date, the commit
# and the machine) and doc/shapes_jeffery_3d.png (LEVELS=3) or
# doc/shapes_jeffery_3d_levelsL.png. LEVELS=3: about 50 minutes and 1.7 GB on one core;
# LEVELS=4: about 90 minutes and 4.2 GB. Run it alone.
#
# Usage: bash benchmarks/jeffery_3d.sh     (EXE=PATH, WORK=DIR, END_TIME=T, LEVELS=L)
set -euo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
exe="${EXE:-$top/build/fdparticle}"
end_time="${END_TIME:-9}"
levels="${LEVELS:-3}"
work="${WORK:-$top/benchmarks/work/jeffery_3d_levels$levels}"
# The spheroid's semi-axes, the base cells across the box of width 2, the time step.
a=0.2 b=0.1 cells=6 dt=0.1
b_over_h="$(/usr/bin/python3 -c "print(round($b / (2 / $cells / 2**$levels), 2))")"
png="$top/doc/shapes_jeffery_3d.png"
[ "$levels" = 3 ] || png="$top/doc/shapes_jeffery_3d_levels$levels.png"
[ -x "$exe" ] || bash "$top/scripts/build.sh"
mkdir -p "$work"
stamp="$(date -u +%Y-%m-%dT%H:%MZ),$(git -C "$top" rev-parse --short HEAD),$(hostname)"

cat > "$work/orbit.prm" <<PRM
set Dimension = 3
set Gravity = 0, 0, 0
subsection Geometry
  set Lower corner = -1, -1, -1
  set Upper corner = 1, 1, 1
  set Subdivisions = $cells, $cells, $cells
  set Periodic directions = x, z
end
subsection Boundary conditions
  set Wall velocities = y+: 1, 0, 0; y-: -1, 0, 0
end
subsection Fluid
  set Density = 1
  set Viscosity = 1
  set Convection = false
end
subsection Particles
  set Particles = 0, 0, 0 : ellipsoid $a, $b, $b, 0, 1, 0, -45 : 1
end
subsection Solver
  set Linear solver = iterative
end
subsection Quadrature
  set Cut cells = level set
end
subsection Refinement
  set Particle refinement levels = $levels
end
subsection Time
  set Time step = $dt
  set End time = $end_time
end
subsection Output
  set VTU interval = 0
  set Directory = $work/orbit
end
PRM
/usr/bin/time -f "%e %M" -o "$work/orbit.time" "$exe" "$work/orbit.prm" > "$work/orbit.log" 2>&1 ||
  { echo "the run failed (see $work/orbit.log)"; exit 1; }
read -r seconds kb < "$work/orbit.time"
result="$(/usr/bin/python3 "$top/benchmarks/jeffery_orbit_3d.py" "$work/orbit" "$a" "$b" 1 1 \
  "$png" | tail -1)"
csv="$top/doc/shapes_jeffery_3d.csv"
header="turned_rad,time_to_turn_error,max_axis_deviation_deg,orbit_constant_start,orbit_constant_drift,b_over_h,dt,end_time,wall_seconds,peak_mb,date,commit,machine"
row="$result,$b_over_h,$dt,$end_time,$seconds,$((kb / 1024)),$stamp"
# Keep the rows of the other b/h; this run's row replaces its own.
{ echo "$header"
  { [ -f "$csv" ] && tail -n +2 "$csv" | awk -F, -v bh="$b_over_h" '$6 != bh'
    echo "$row"; } | sort -t, -k6,6g
} > "$csv.new"
mv "$csv.new" "$csv"
cat "$csv"
