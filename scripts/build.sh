#!/usr/bin/env bash
# Configure and build fdparticle and its tests: Release in build/ (the default), or with
# `--debug` a Debug build in build-debug/ that links deal.II's debug library, so that
# deal.II's Assert checks (index ranges, vector layouts, ...) run. Arguments -DNAME=VALUE
# go to cmake (e.g. -DFDPARTICLE_DEBUG_INFO=OFF); the others name the targets to build
# (default: all).
set -euo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
type=Release
dir="$top/build"
if [ "${1:-}" = "--debug" ]; then
  type=Debug
  dir="$top/build-debug"
  shift
fi
options=()
targets=()
for arg in "$@"; do
  case "$arg" in
    -D*) options+=("$arg") ;;
    *) targets+=("$arg") ;;
  esac
done
cmake -S "$top" -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=$type "${options[@]}" \
  > "$dir.configure.log" 2>&1 || { cat "$dir.configure.log"; exit 1; }
if [ ${#targets[@]} -gt 0 ]; then
  cmake --build "$dir" -j "$(nproc)" --target "${targets[@]}"
else
  cmake --build "$dir" -j "$(nproc)"
fi
