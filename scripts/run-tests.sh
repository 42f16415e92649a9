#!/usr/bin/env bash
# Install dependencies, build, and run the whole ctest suite. This is the command CI runs.
set -euo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
bash "$top/scripts/install-dependencies.sh"
bash "$top/scripts/build.sh"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
cd "$top/build"
ctest --output-on-failure -j "$(nproc)" "$@"
