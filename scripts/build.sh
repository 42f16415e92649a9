#!/usr/bin/env bash
# Configure (Release) and build fdparticle and its tests in build/.
set -euo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
cmake -S "$top" -B "$top/build" -G Ninja -DCMAKE_BUILD_TYPE=Release > "$top/build-configure.log" || {
  cat "$top/build-configure.log"; exit 1; }
cmake --build "$top/build" -j "$(nproc)"
