#!/usr/bin/env bash
# Configure and build fdparticle and its tests: Release in build/ (the default), or with
# `--debug` a Debug build in build-debug/ that links deal.II's debug library, so that
# deal.II's Assert checks (index ranges, vector layouts, ...) run. Further arguments name
# the targets to build (default: all).
set -euo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
type=Release
dir="$top/build"
if [ "${1:-}" = "--debug" ]; then
  type=Debug
  dir="$top/build-debug"
  shift
fi
cmake -S "$top" -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=$type > "$dir.configure.log" 2>&1 || {
  cat "$dir.configure.log"; exit 1; }
if [ $# -gt 0 ]; then
  cmake --build "$dir" -j "$(nproc)" --target "$@"
else
  cmake --build "$dir" -j "$(nproc)"
fi
