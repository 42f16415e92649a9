#!/usr/bin/env bash
# Newton's initial guess (doc/method.md §5, `Solver/Initial guess`): each scene run to the
# same end time from the extrapolated state and from the last step's, on RANKS ranks:
#   cavity2d     prm/cavity2d.prm to t = 0.3 (Navier-Stokes, direct solver)
#   sediment2d   prm/sediment2d.prm to t = 3 (Navier-Stokes, a wall repulsion at the end)
#   dkt2d        prm/dkt2d.prm to t = 3 (drafting, kissing: the collision force acts)
#   cavity3d     prm/cavity.prm with the adaptive level-set settings of doc/smoothness.md,
#                iterative solver, to t = 0.08
#   sediment3d   the same for prm/sediment.prm, to t = 0.3
# Writes doc/initial_guess.csv, one row per run: steps, Newton iterations and linear
# iterations per step (the direct solver counts one per solve), the fraction of the steps
# that started from the extrapolated state, the wall time of the steps (statistics.csv's
# wall_seconds summed: without the start-up, which the first run of a cold machine pays),
# the run's wall time and peak memory of one rank, the largest difference of a particle's
# final velocity from the run with the other guess relative to its largest component,
# then the date and the commit.
# Usage: [SCENES="cavity2d sediment2d dkt2d cavity3d sediment3d"] [RANKS=1]
#        bash benchmarks/initial_guess.sh   (~30 min; alone on the machine)
set -uo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
exe="${EXE:-$top/build/fdparticle}"
work="${WORK:-$top/benchmarks/work/initial_guess}"
ranks="${RANKS:-1}"
scenes="${SCENES:-cavity2d sediment2d dkt2d cavity3d sediment3d}"
[ -x "$exe" ] || bash "$top/scripts/build.sh"
mkdir -p "$work"
. "$top/benchmarks/scaling_scenes.sh"
csv="$top/doc/initial_guess.csv"
date=$(date -u +%Y-%m-%d); commit=$(git -C "$top" rev-parse --short HEAD)

scene() { # name guess directory -> prm on stdout
  local base end
  case $1 in
    cavity2d)   base=cavity2d;   end=0.3 ;;
    sediment2d) base=sediment2d; end=3 ;;
    dkt2d)      base=dkt2d;      end=3 ;;
    cavity3d)   base=cavity;     end=0.08 ;;
    sediment3d) base=sediment;   end=0.3 ;;
  esac
  cat "$top/prm/$base.prm"
  case $1 in
    *3d) adaptive_levelset
         printf 'subsection Solver\n  set Linear solver = iterative\nend\n' ;;
  esac
  printf 'subsection Solver\n  set Initial guess = %s\nend\n' "$2"
  printf 'subsection Time\n  set End time = %s\nend\n' "$end"
  printf 'subsection Output\n  set Directory = %s\n  set VTU interval = 0\nend\n' "$3"
}

# The last row's velocity of each particle: "id vx vy [vz]" lines.
final_velocities() {
  awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i; next }
           { line[$col["id"]] = $0 }
           END { for (k in line) { split(line[k], f, ",")
                   printf "%s %s %s %s\n", k, f[col["vx"]], f[col["vy"]], ("vz" in col) ? f[col["vz"]] : 0 } }' "$1"
}

echo "scene,guess,ranks,dofs_last,steps,newton_per_step,linear_per_step,extrapolated_fraction,step_seconds,run_seconds,peak_mb,velocity_difference,date,commit" > "$csv"
for name in $scenes; do
  rows=()
  for guess in extrapolated "last step"; do
    d="$work/$name-${guess// /_}"
    rm -rf "$d"; mkdir -p "$d"
    scene "$name" "$guess" "$d/out" > "$d/scene.prm"
    if ! /usr/bin/time -f "%e %M" -o "$d/time" \
         bash "$top/scripts/mpirun.sh" "$ranks" "$exe" "$d/scene.prm" > "$d/log" 2>&1; then
      echo "$name ($guess) failed (see $d/log)"
      continue
    fi
    read -r seconds kb < "$d/time"
    counts=$(awk -F, '
      NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i; next }
      { n++; newton += $col["nonlinear_iterations"]; linear += $col["linear_iterations"]
        extrapolated += $col["extrapolated_start"]; seconds += $col["wall_seconds"]; dofs = $col["dofs"] }
      END { printf "%d,%d,%.2f,%.2f,%.2f,%.2f", dofs, n, newton / n, linear / n, extrapolated / n,
                   seconds }' "$d/out/statistics.csv")
    final_velocities "$d/out/particles.csv" | sort > "$d/velocities"
    rows+=("$name,$guess,$ranks,$counts,$seconds,$((kb / 1024))")
  done
  [ ${#rows[@]} -eq 2 ] || continue
  a="$work/$name-extrapolated/velocities"; b="$work/$name-last_step/velocities"
  difference=$(paste -d' ' "$a" "$b" | awk '
    { s = 0; m = 0
      for (i = 2; i <= 4; i++) { e = $i - $(i + 4); if (e < 0) e = -e; if (e > m) m = e
                                 v = $(i + 4); if (v < 0) v = -v; if (v > s) s = v }
      r = s > 0 ? m / s : m; if (r > worst) worst = r }
    END { printf "%.2e", worst }')
  for row in "${rows[@]}"; do echo "$row,$difference,$date,$commit" | tee -a "$csv"; done
done
