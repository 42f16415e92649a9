#!/usr/bin/env bash
# Robustness of the iterative linear solver (doc/scaling.md): FGMRES and inner iterations
# of the first step of the seed's 3D sediment scene (box 1 x 2 x 1, Stokes, Subdivisions
# N x 2N x N, default N = 6) when one parameter moves away from the base scene
# (dt = 0.1, rho_f = 1, rho_P = 1.5, mu = 1, one sphere R = 0.2):
#   dt 1e-4 ... 10, rho_P / rho_f 0.01 ... 1000, mu 1e-3 ... 1e3, and 1, 8, 64 spheres
#   (R = 0.2, 0.1, 0.05 on a lattice in the lower cube) on the same mesh.
# Writes doc/robustness.csv (case, value, unknowns, FGMRES iterations, inner iterations,
# wall seconds of the run, peak MB, date, commit); a failed run leaves its row empty.
# Usage: bash benchmarks/robustness.sh     (~5 min on 2 cores)
set -uo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
exe="${EXE:-$top/build/fdparticle}"
work="${WORK:-$top/benchmarks/work/robustness}"
n="${N:-6}"
[ -x "$exe" ] || bash "$top/scripts/build.sh"
mkdir -p "$work"

lattice() { # k R density: k^3 spheres of radius R in the cube [-0.5, 0.5]^3
  awk -v k="$1" -v r="$2" -v rho="$3" 'BEGIN {
    s = "";
    for (i = 0; i < k; ++i) for (j = 0; j < k; ++j) for (l = 0; l < k; ++l)
      s = s (s == "" ? "" : "; ") sprintf("%g, %g, %g : %g : %g",
            -0.5 + (i + 0.5) / k, -0.5 + (j + 0.5) / k, -0.5 + (l + 0.5) / k, r, rho);
    print s }'
}

scene() { # dt mu particles
  printf 'set Dimension = 3\nset Gravity = 0, -10, 0\n'
  printf 'subsection Geometry\n  set Lower corner = -0.5, -0.5, -0.5\n'
  printf '  set Upper corner = 0.5, 1.5, 0.5\n  set Subdivisions = %s, %s, %s\nend\n' "$n" $((2 * n)) "$n"
  printf 'subsection Fluid\n  set Viscosity = %s\n  set Convection = false\nend\n' "$2"
  printf 'subsection Particles\n  set Particles = %s\nend\n' "$3"
  printf 'subsection Time\n  set End time = %s\n  set Time step = %s\nend\n' "$1" "$1"
  printf 'subsection Solver\n  set Linear solver = iterative\nend\n'
}

csv="$top/doc/robustness.csv"
echo "case,value,dofs,linear_iterations,inner_iterations,wall_seconds,peak_mb,date,commit" > "$csv"
commit=$(git -C "$top" rev-parse --short HEAD 2>/dev/null || echo unknown)
run() { # case value dt mu particles
  d="$work/$1-$2"
  mkdir -p "$d"
  { scene "$3" "$4" "$5"
    printf 'subsection Output\n  set Directory = %s\n  set VTU interval = 0\nend\n' "$d/out"
  } > "$d/scene.prm"
  if ! /usr/bin/time -f "%e %M" -o "$d/time" "$exe" "$d/scene.prm" > "$d/log" 2>&1; then
    echo "$1 $2 failed (see $d/log)"
    echo "$1,$2,,,,,,$(date -u +%F),$commit" >> "$csv"
    return
  fi
  read -r wall kb < "$d/time"
  echo "$1,$2,$(bash "$top/scripts/statistics-columns.sh" "$d/out/statistics.csv" 1 dofs linear_iterations inner_iterations),$wall,$((kb / 1024)),$(date -u +%F),$commit" | tee -a "$csv"
}

one="0, 1, 0 : 0.2"
for dt in 1e-4 1e-2 0.1 1 10; do run dt "$dt" "$dt" 1 "$one : 1.5"; done
for rho in 0.01 0.1 1 10 1000; do run density_ratio "$rho" 0.1 1 "$one : $rho"; done
for mu in 1e-3 1e-1 1 10 1e3; do run viscosity "$mu" 0.1 "$mu" "$one : 1.5"; done
run particles 1 0.1 1 "$(lattice 1 0.2 1.5)"
run particles 8 0.1 1 "$(lattice 2 0.1 1.5)"
run particles 64 0.1 1 "$(lattice 4 0.05 1.5)"
