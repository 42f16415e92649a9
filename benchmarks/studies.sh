#!/usr/bin/env bash
# Regenerates the convergence studies of doc/studies.md with tools/fdparticle-study:
#   doc/studies/reference_2d/  uniform 64 x 128, level set (~1 min): the uniform mesh that
#                              space_2d's "following, 3 levels" runs are compared with
#   doc/studies/space_2d/  2D settling disk: uniform vs particle-following refinement,
#                          Gauss 3/7/10 vs level-set cut-cell quadrature (28 runs, ~2 min)
#   doc/studies/time_2d/   2D settling disk (Stokes): BDF1 vs BDF2, seed vs fixed pairing,
#                          dt = 0.04 / 2^k, k = 0..4 (20 runs, ~3 min)
#   doc/studies/dt_2d/     2D settling disk (Stokes, 32 x 64): terminal velocity vs dt = 0.0125 ... 2,
#                          BDF1 and BDF2, seed vs fixed pairing (32 runs, ~15 min)
# Usage (from anywhere; serial runs, one at a time):
#   bash benchmarks/studies.sh [reference_2d] [space_2d] [time_2d] [dt_2d] [space_3d]   # default: all
# FDPARTICLE=path/to/fdparticle overrides the program (default build/fdparticle, built if
# missing). space_3d: the periodic cubic array of spheres (steady, one solve per run).
set -euo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
cd "$top"
# Paths relative to the top of the repository, so that the command each study.md records
# holds no machine-specific directory.
exe="${FDPARTICLE:-build/fdparticle}"
[ -x "$exe" ] || bash "$top/scripts/build.sh"
studies=("$@")
[ ${#studies[@]} -gt 0 ] || studies=(reference_2d space_2d time_2d dt_2d space_3d space_3d_small)
# The runs themselves (prm, output, logs) go to $STUDY_WORK (default output/studies, ignored
# by git); rerunning with the same work directory reuses finished runs (--reuse).
work="${STUDY_WORK:-output/studies}"
mkdir -p "$work"

study() { # BASE NAME [fdparticle-study options]: runs in $work/NAME, results in doc/studies/NAME
  local base=$1 name=$2
  shift 2
  tools/fdparticle-study "$base" --executable "$exe" --keep-going --reuse --work "$work/$name" \
    "$@" --output "doc/studies/$name"
}
time_study() { # NAME REFINEMENTS END_TIME TIME_STEPS QOIS: BDF1 vs BDF2 on a fixed uniform
               # mesh (Stokes, level set), each scheme against its own finest time step, with
               # the seed's pairing (alpha from the current dt) and with a fixed pairing time
               # step (Multiplier/Pairing time step = 0.1: the discrete constraint no longer
               # changes with dt)
  study prm/sediment2d.prm "$1" --set "Time/End time=$3" --set "Geometry/Global refinements=$2" \
    --set "Fluid/Convection=false" --set "Quadrature/Cut cells=level set" \
    --vary "Multiplier/Pairing time step=0,0.1" \
    --vary "Time/Scheme=BDF1,BDF2" --vary "Time/Time step=$4" --qoi "$5" --reference group-finest
}
array_study() { # NAME MESHES REFERENCE_U [options]: the periodic cubic array of fixed spheres,
                # QoI the superficial velocity mean_vx, Gauss 7 against level set
  local name=$1 meshes=$2 reference=$3
  shift 3
  study prm/validation/array3d.prm "$name" "$@" \
    --vary "@mesh|Geometry/Global refinements|Refinement/Particle refinement levels=$meshes" \
    --vary "Quadrature/Cut cells|Quadrature/Gauss points in cut cells=gauss|7,level set|7" \
    --qoi mean_vx --reference "$reference"
}

for study in "${studies[@]}"; do
  case "$study" in
    reference_2d)
      # One run on the uniform 64 x 128 mesh (157k unknowns, ~40 s).
      study prm/sediment2d.prm reference_2d \
        --set "Time/End time=2" --set "Geometry/Global refinements=3" \
        --set "Quadrature/Cut cells=level set" \
        --qoi terminal-vy,vy-at:1,terminal-fy
      ;;
    space_2d)
      # Mesh series x quadrature (Cartesian product, 32 runs, ~6 min). Reference: the
      # uniform 64 x 128 level-set run of reference_2d (-0.0117249; 32 x 64 is 0.14 % off):
      # following refinement on the 8 x 16 base converges to a value 0.7 % away, the error of
      # the coarse far field, so its own finest run is not the reference (doc/studies.md). 5 levels
      # (h = 1/256) is included since MUMPS retries with more working space (ICNTL(14)).
      study prm/sediment2d.prm space_2d \
        --set "Time/End time=2" \
        --vary "@mesh|Geometry/Global refinements|Refinement/Particle refinement levels=uniform|0|0,uniform|1|0,uniform|2|0,following|0|1,following|0|2,following|0|3,following|0|4,following|0|5" \
        --vary "Quadrature/Cut cells|Quadrature/Gauss points in cut cells=gauss|3,gauss|7,gauss|10,level set|7" \
        --qoi terminal-vy,vy-at:1,terminal-fy \
        --reference -0.0117249
      ;;
    time_2d)
      # Fixed mesh (16 x 32, level-set rules, Stokes), each scheme and pairing against its
      # own finest time step; QoI: the particle's height at t = 0.2 (before the first cell
      # changes state) and at t = 0.4 (after one has, near t = 0.24).
      time_study time_2d 1 0.4 0.04,0.02,0.01,0.005,0.0025 y-at:0.2,y-at:0.4,vy-at:0.2
      ;;
    space_3d)
      # 3D, steady: the cubic array of fixed spheres (c = 0.064, prm/validation/array3d.prm),
      # QoI the superficial velocity U = mean_vx, reference Zick & Homsy's K = 2.810:
      # U = 1/(6 pi mu a K) = 0.0760855. Uniform 8^3, 16^3 against following 4^3 + 1, 2, 3
      # levels (the same surface h up to d/h = 8; d/h = 16 following only: uniform 32^3
      # would be 1.8 M unknowns), Gauss 7 against level set (10 runs).
      # (The settling sphere of prm/sediment.prm costs 150 s per step with 2 levels.)
      array_study space_3d "uniform|1|0,uniform|2|0,following|0|1,following|0|2,following|0|3" 0.0760855
      ;;
    space_3d_small)
      # The same with a small sphere, c = 0.008 (a = 0.124070; the box is 8 diameters):
      # reference from the Hasimoto / Sangani & Acrivos series (doc/references/README.md,
      # good for c <~ 0.2): K = 1.524646, U = 1/(6 pi mu a K) = 0.2804548. Uniform 8^3, 16^3,
      # 32^3 against following 4^3 + 2, 3, 4 levels, Gauss 7 against level set (12 runs);
      # Linear solver = auto from 500 k unknowns: the direct solver below, the iterative one
      # on uniform 32^3 (1.8 M unknowns), where MUMPS cannot allocate its factors in 24 GB.
      array_study space_3d_small "uniform|1|0,uniform|2|0,uniform|3|0,following|0|2,following|0|3,following|0|4" 0.2804548 \
        --set "Particles/Particles=0.5, 0.5, 0.5 : 0.124070 : 1 : fixed" --set "Solver/Linear solver=auto" \
        --set "Solver/Iterative solver from=500000"
      ;;
    dt_2d)
      # Fixed mesh (32 x 64, level-set rules, Stokes), dt = 0.0125 ... 2 to t = 6 (~7 min):
      # the terminal velocity must not depend on dt (fluid penalty weight of 78b701a).
      time_study dt_2d 2 6 0.0125,0.025,0.05,0.1,0.2,0.5,1,2 vy-at:6,terminal-vy,y-at:6
      ;;
    *) echo "unknown study '$study' (reference_2d, space_2d, time_2d, dt_2d, space_3d, space_3d_small)" >&2; exit 1 ;;
  esac
done
