#!/usr/bin/env bash
# Install dependencies, build, and run one scene: scripts/run-scene.sh [-np N] prm/sediment.prm
set -euo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
ranks=1
if [ "${1:-}" = "-np" ]; then ranks="$2"; shift 2; fi
[ $# -ge 1 ] || { echo "usage: scripts/run-scene.sh [-np N] FILE.prm" >&2; exit 2; }
bash "$top/scripts/install-dependencies.sh"
bash "$top/scripts/build.sh"
if [ "$ranks" -gt 1 ]; then
  exec bash "$top/scripts/mpirun.sh" "$ranks" "$top/build/fdparticle" "$@"
fi
exec "$top/build/fdparticle" "$@"
