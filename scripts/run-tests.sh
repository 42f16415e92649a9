#!/usr/bin/env bash
# Install dependencies, build, and run the ctest suite. This is the command CI runs.
#   bash scripts/run-tests.sh            Release build, the whole suite
#   bash scripts/run-tests.sh --debug    Debug build (deal.II's assertions on), the tests
#                                        in debug_tests below
#   ... --build-only                     build what the tests need, run none
# Further arguments go to ctest.
set -euo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
bash "$top/scripts/install-dependencies.sh"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# The Debug build runs 10-30 times slower, so CI runs there one test of each code path:
# the fast unit tests (the shapes' contact geometry among them), input errors (checkpoints
# read and refused), Stokes and Navier-Stokes, recovery (and its checkpoint), periodic
# directions and adaptive refinement on 2 ranks. restart_2d and the mirror tests take over
# ten minutes each there.
debug_units='assembly_terms collisions direct_solver newton_solver cut_cell_quadrature parameters particle_refinement pressure_agglomeration rigid_body time_stepper velocity_operator'
debug_tests="^unit/(${debug_units// /|})\$"
debug_tests+='|^bad_|^(regression_sediment_2d|regression_cavity_2d|recovery_2d|recovery_exhausted_2d'
debug_tests+='|stability_tiny_dt_2d|validation_array_2d|hydrostatic_2d_zero|mpi_adaptive_2d)$'
# One test more than there are cores: a test on 1 and 2 ranks reserves two cores for all its
# runs, so while its 1-rank run goes one core would idle.
jobs=$(( $(nproc) + 1 ))
debug=0
build_only=0
while [ $# -gt 0 ]; do
  case "$1" in
    --debug) debug=1 ;;
    --build-only) build_only=1 ;;
    *) break ;;
  esac
  shift
done
if [ $debug = 1 ]; then
  # Only what these tests run: the program and their unit tests, without debug
  # information (the assertions are what this build is for; it compiles two fifths faster).
  targets=(-DFDPARTICLE_DEBUG_INFO=OFF fdparticle)
  for unit in $debug_units; do targets+=("unit_$unit"); done
  bash "$top/scripts/build.sh" --debug "${targets[@]}"
  [ $build_only = 1 ] && exit 0
  cd "$top/build-debug"
  ctest --output-on-failure -j "$jobs" -R "$debug_tests" "$@"
else
  bash "$top/scripts/build.sh"
  [ $build_only = 1 ] && exit 0
  cd "$top/build"
  ctest --output-on-failure -j "$jobs" "$@"
fi
