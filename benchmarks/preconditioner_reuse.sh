#!/usr/bin/env bash
# What reusing the iterative solver's preconditioner saves (doc/performance.md): two 3D
# Navier-Stokes scenes with particle-following refinement, run with `Linear solver =
# iterative` and `Reuse preconditioner` false (a new preconditioner for every Jacobian) and
# true, one after the other so that both see the same machine load:
#   cavity  prm/cavity.prm with 2 particle refinement levels and the level-set rule
#           (198 k unknowns; the adaptls variant of doc/smoothness.md), 3 steps
#   dkt3d   prm/dkt3d.prm (d/h = 4, 147-154 k unknowns), 6 steps
# For each run: steps, Jacobians, preconditioner builds, FGMRES iterations, wall seconds
# (statistics.csv) and peak memory. Appends to doc/preconditioner_reuse.csv (the header is
# written when the file is new), so that a run with another build can be added.
#
# Usage (regenerate):
#   bash benchmarks/preconditioner_reuse.sh
# EXE=PATH runs another executable; LABEL=NAME names it in the table (default: the
# commit of the source tree); REUSE="true" runs one setting only; WORK=DIR keeps the runs.
set -euo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
exe="${EXE:-$top/build/fdparticle}"
[ -x "$exe" ] || bash "$top/scripts/build.sh"
label="${LABEL:-$(git -C "$top" rev-parse --short HEAD)}"
work="${WORK:-$(mktemp -d)}"
csv="$top/doc/preconditioner_reuse.csv"
. "$top/benchmarks/scaling_scenes.sh"
[ -f "$csv" ] || echo "build,scene,reuse,steps,jacobians,preconditioner_builds,fgmres,wall_seconds,peak_mb" > "$csv"

scene_prm() { # scene -> the prm on stdout (output directory and end time set by run)
  case $1 in
    cavity) cat "$top/prm/cavity.prm"
            adaptive_levelset ;;
    dkt3d) cat "$top/prm/dkt3d.prm" ;;
  esac
}

run() { # scene steps reuse
  local d="$work/$label-$1-$3" dt
  mkdir -p "$d"
  dt=$(scene_prm "$1" | sed -n 's/^\s*set Time step\s*=\s*//p' | tail -1)
  {
    scene_prm "$1" | sed -e "s#^\(\s*set Directory\s*=\).*#\1 $d/out#" \
                         -e "s/^\(\s*set VTU interval\s*=\).*/\1 0/" \
                         -e "s/^\(\s*set End time\s*=\).*/\1 $(awk -v n="$2" -v dt="$dt" 'BEGIN { print n * dt }')/"
    printf 'subsection Solver\n  set Linear solver = iterative\n  set Reuse preconditioner = %s\n' "$3"
    printf '  set Iterative solver statistics = true\nend\n'
  } > "$d/scene.prm"
  /usr/bin/time -f "%M" -o "$d/memory" "$exe" "$d/scene.prm" > "$d/log" 2>&1 ||
    { echo "$1 reuse=$3 failed (see $d/log)"; return; }
  # Builds are counted in the solver's statistics lines, so that a build without the
  # jacobians column (before it existed) can be measured too.
  awk -F, -v label="$label" -v scene="$1" -v reuse="$3" -v kb="$(tail -1 "$d/memory")" \
      -v builds="$(grep -c 'preconditioner built' "$d/log")" '
    NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
    { n++; if ("jacobians" in c) j += $c["jacobians"]; f += $c["linear_iterations"]
      w += $c["wall_seconds"] }
    END { printf "%s,%s,%s,%d,%s,%d,%d,%.1f,%d\n", label, scene, reuse, n,
                 ("jacobians" in c) ? j : "", builds, f, w, kb / 1024 }' \
    "$d/out/statistics.csv" | tee -a "$csv"
}

for reuse in ${REUSE:-false true}; do
  run cavity 3 "$reuse"
  run dkt3d 6 "$reuse"
done
column -s, -t "$csv"
