#!/usr/bin/env bash
# Configure and build fdparticle and its tests: Release in build/ (the default), or with
# `--debug` a Debug build in build-debug/ that links deal.II's debug library, so that
# deal.II's Assert checks (index ranges, vector layouts, ...) run.
set -euo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
type=Release
dir="$top/build"
if [ "${1:-}" = "--debug" ]; then
  type=Debug
  dir="$top/build-debug"
fi
cmake -S "$top" -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=$type > "$dir.configure.log" 2>&1 || {
  cat "$dir.configure.log"; exit 1; }
cmake --build "$dir" -j "$(nproc)"
