#!/usr/bin/env bash
# Install dependencies, build, and run the ctest suite. This is the command CI runs.
#   bash scripts/run-tests.sh            Release build, the whole suite
#   bash scripts/run-tests.sh --debug    Debug build (deal.II's assertions on), the unit
#                                        tests and the 2D scene tests
# Further arguments go to ctest.
set -euo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
bash "$top/scripts/install-dependencies.sh"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
if [ "${1:-}" = "--debug" ]; then
  shift
  bash "$top/scripts/build.sh" --debug
  cd "$top/build-debug"
  ctest --output-on-failure -j "$(nproc)" -R '^unit/|_2d$' "$@"
else
  bash "$top/scripts/build.sh"
  cd "$top/build"
  ctest --output-on-failure -j "$(nproc)" "$@"
fi
