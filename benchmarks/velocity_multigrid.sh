#!/usr/bin/env bash
# A geometric multigrid V-cycle on the matrix-free velocity operator against one V-cycle of
# ML on the assembled matrix (the block preconditioner's velocity block today), each as the
# preconditioner of GMRES on A_uu x = b to 1e-8 (benchmarks/velocity_multigrid.cc): the
# unit cube of N0^3 cells refined L times, Q2 velocity, Navier–Stokes coefficients. One
# row of doc/velocity_multigrid.csv per mesh and rank count: set-up seconds, GMRES
# iterations and solve seconds of each; the assembly of the matrix that ML needs apart.
#
# Usage (regenerate):  bash benchmarks/velocity_multigrid.sh
# MESHES="4:2 4:3 5:3" overrides the meshes (N0:L), EXE the benchmark program.
set -euo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
exe="${EXE:-$top/build/velocity_multigrid_benchmark}"
[ -x "$exe" ] || bash "$top/scripts/build.sh" velocity_multigrid_benchmark
csv="$top/doc/velocity_multigrid.csv"
meshes="${MESHES:-4:2 4:3 5:3}"
date=$(date -u +%Y-%m-%d); commit=$(git -C "$top" rev-parse --short HEAD)
echo "ranks,cells,unknowns,levels,gmg_setup_s,gmg_iterations,gmg_solve_s,matrix_assembly_s,ml_setup_s,ml_iterations,ml_solve_s,date,commit" > "$csv"
for mesh in $meshes; do
  for ranks in 1 2; do
    if [ "$ranks" = 1 ]; then row=$("$exe" "${mesh%:*}" "${mesh#*:}")
    else row=$(bash "$top/scripts/mpirun.sh" "$ranks" "$exe" "${mesh%:*}" "${mesh#*:}"); fi
    echo "$row,$date,$commit" | tee -a "$csv"
  done
done
column -s, -t "$csv"
