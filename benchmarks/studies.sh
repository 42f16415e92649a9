#!/usr/bin/env bash
# Regenerates the convergence studies of doc/studies.md with tools/fdparticle-study:
#   doc/studies/reference_2d/  the reference of space_2d: uniform 64 x 128, level set (~4 min)
#   doc/studies/space_2d/  2D settling disk: uniform vs particle-following refinement,
#                          Gauss 3/7/10 vs level-set cut-cell quadrature (28 runs, ~6 min)
#   doc/studies/time_2d/   2D settling disk (Stokes): BDF1 vs BDF2, dt = 0.1 / 2^k, k = 0..4
#                          (10 runs, ~2 min)
# Usage (from anywhere; serial runs, one at a time):
#   bash benchmarks/studies.sh [reference_2d] [space_2d] [time_2d] [space_3d]   # default: the 2D ones
# FDPARTICLE=path/to/fdparticle overrides the program (default build/fdparticle, built if
# missing). space_3d is the 3D counterpart; it was not run for doc/studies.md (hours on a
# 2-core machine; see there).
set -euo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
cd "$top"
exe="${FDPARTICLE:-$top/build/fdparticle}"
[ -x "$exe" ] || bash "$top/scripts/build.sh"
studies=("$@")
[ ${#studies[@]} -gt 0 ] || studies=(reference_2d space_2d time_2d)
# The runs themselves (prm, output, logs) go to $STUDY_WORK (default output/studies, ignored
# by git); rerunning with the same work directory reuses finished runs (--reuse).
work="${STUDY_WORK:-$top/output/studies}"
mkdir -p "$work"

for study in "${studies[@]}"; do
  case "$study" in
    reference_2d)
      # One run on the uniform 64 x 128 mesh (157k unknowns, ~4 min): the reference of space_2d.
      tools/fdparticle-study prm/sediment2d.prm --executable "$exe" --keep-going --reuse --work "$work/reference_2d" \
        --set "Time/End time=2" --set "Geometry/Global refinements=3" \
        --set "Quadrature/Cut cells=level set" \
        --qoi terminal-vy,vy-at:1,terminal-fy --output doc/studies/reference_2d
      ;;
    space_2d)
      # Mesh series x quadrature (Cartesian product, 28 runs, ~6 min). Reference: the
      # uniform 64 x 128 level-set run of reference_2d (run that first).
      ref="$(awk -F, 'NR == 1 {for (i = 1; i <= NF; i++) if ($i == "qoi") c = i} NR == 2 {print $c}' doc/studies/reference_2d/study.csv)"
      tools/fdparticle-study prm/sediment2d.prm --executable "$exe" --keep-going --reuse --work "$work/space_2d" \
        --set "Time/End time=2" \
        --vary "@mesh|Geometry/Global refinements|Refinement/Particle refinement levels=uniform|0|0,uniform|1|0,uniform|2|0,following|0|1,following|0|2,following|0|3,following|0|4" \
        --vary "Quadrature/Cut cells|Quadrature/Gauss points in cut cells=gauss|3,gauss|7,gauss|10,level set|7" \
        --qoi terminal-vy,vy-at:1,terminal-fy \
        --reference "$ref" --output doc/studies/space_2d
      ;;
    time_2d)
      # Fixed mesh (16 x 32, level-set rules, Stokes), each scheme against its own
      # finest time step; QoI: the particle's height at t = 1.
      tools/fdparticle-study prm/sediment2d.prm --executable "$exe" --keep-going --reuse --work "$work/time_2d" \
        --set "Time/End time=1" --set "Geometry/Global refinements=1" \
        --set "Fluid/Convection=false" --set "Quadrature/Cut cells=level set" \
        --vary "Time/Scheme=BDF1,BDF2" \
        --vary "Time/Time step=0.1,0.05,0.025,0.0125,0.00625" \
        --qoi y-at:1,vy-at:1 --reference group-finest --output doc/studies/time_2d
      ;;
    space_3d)
      # Not run for doc/studies.md: 3D is ~10 s per step on the 8 x 16 x 8 base alone.
      tools/fdparticle-study prm/sediment.prm --executable "$exe" --keep-going --reuse --work "$work/space_3d" \
        --set "Time/End time=1" \
        --vary "@mesh|Geometry/Global refinements|Refinement/Particle refinement levels=uniform|0|0,uniform|1|0,following|0|1,following|0|2" \
        --vary "Quadrature/Cut cells|Quadrature/Gauss points in cut cells=gauss|7,level set|7" \
        --qoi terminal-vy --reference run:8 --output doc/studies/space_3d
      ;;
    *) echo "unknown study '$study' (reference_2d, space_2d, time_2d, space_3d)" >&2; exit 1 ;;
  esac
done
