#!/usr/bin/env bash
# The velocity block of the Newton matrix, matrix-free (VelocityOperator) against the
# assembled Epetra matrix of the same bilinear form (benchmarks/velocity_operator.cc): the
# unit cube with N^3 cells, Q2 velocity, Navier–Stokes coefficients. For each N and 1 and 2
# ranks one row of doc/velocity_operator.csv: set-up and best product seconds of each,
# rates in million unknowns per second, their ratio, bytes held per unknown; beside them
# the machine's triad bandwidth (benchmarks/memory_bandwidth.sh), which bounds the rate at
# bandwidth / (bytes streamed per unknown). Run alone; the ratio is what compares.
#
# Usage (regenerate):  bash benchmarks/velocity_operator.sh
# SIZES="16 24 35" overrides the meshes (35: 1.07 M unknowns), EXE the benchmark program.
set -euo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
exe="${EXE:-$top/build/velocity_operator_benchmark}"
[ -x "$exe" ] || bash "$top/scripts/build.sh" velocity_operator_benchmark
csv="$top/doc/velocity_operator.csv"
sizes="${SIZES:-16 24 35}"
bandwidth=$(bash "$top/benchmarks/memory_bandwidth.sh" | sed -n 's/.*one process alone \([0-9.]*\) GB.s.*/\1/p')
date=$(date -u +%Y-%m-%d); commit=$(git -C "$top" rev-parse --short HEAD)
echo "ranks,cells,unknowns,mf_setup_s,mf_product_s,matrix_setup_s,matrix_product_s,mf_munknowns_per_s,matrix_munknowns_per_s,matrix_over_mf_time,mf_bytes_per_unknown,matrix_bytes_per_unknown,relative_difference,triad_gb_per_s,date,commit" > "$csv"
for n in $sizes; do
  for ranks in 1 2; do
    if [ "$ranks" = 1 ]; then row=$("$exe" "$n" 20)
    else row=$(bash "$top/scripts/mpirun.sh" "$ranks" "$exe" "$n" 20); fi
    echo "$row,$bandwidth,$date,$commit" | tee -a "$csv"
  done
done
column -s, -t "$csv"
