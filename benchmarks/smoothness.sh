#!/usr/bin/env bash
# Smoothness of particle trajectories (doc/smoothness.md): the seed's sediment scene
# (prm/sediment.prm, 8 x 16 x 8, dt = 0.1) and cavity scene (prm/cavity.prm, 10^3,
# dt = 0.01), or their 2D counterparts (prm/sediment2d.prm, prm/cavity2d.prm: scene names
# sediment2d, cavity2d), in the variants
#   seed      uniform mesh, 7-point Gauss in cut cells (the seed's method)
#   levelset  uniform mesh, level-set cut-cell quadrature
#   adaptive  2 particle refinement levels, 7-point Gauss
#   adaptls   2 particle refinement levels, level-set quadrature
#   VARIANTold  the variant without the penalty ramp (Penalty ramp = 0, Strain penalty = 0.05,
#             Interior pressure penalty = 1; doc/method.md §4); seedold is the seed's method
#   rampold   adaptls with the ramp but the interior pressure penalty of the seed
#             (Interior pressure penalty = 1)
#   VARIANTit   the variant with the iterative linear solver (Linear solver = iterative); the
#             others use the scene's solver (direct)
# Each run checkpoints every 20 steps into a persistent work directory and resumes from
# there when started again, so the long runs can be spread over several invocations.
# After the runs, doc/smoothness.csv (one row per run) and doc/smoothness_SCENE.png
# (V_y(t) or omega_z(t) of every variant on one figure) are rewritten from whatever
# the work directory holds (runs that have not reached their end are marked 'partial').
#
# Usage (regenerate):
#   bash benchmarks/smoothness.sh sediment:seed:100 sediment:levelset:100 cavity:seed:5 ...
#   bash benchmarks/smoothness.sh sediment2d:{seed,levelset,adaptive,adaptls}:100
#   bash benchmarks/smoothness.sh --report          (only the table and plots)
# Each argument is SCENE:VARIANT:END_TIME. WORK=DIR overrides the work directory, EXE=PATH
# the executable, RANKS=N runs on N MPI ranks (default 1). TAG=NAME writes doc/smoothness_NAME.csv and doc/smoothness_SCENE_NAME.png
# instead, so runs over a shorter window (in their own work directory) keep the full runs'
# table and figures.
set -uo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
exe="${EXE:-$top/build/fdparticle}"
work="${WORK:-$top/benchmarks/work/smoothness}"
mkdir -p "$work"
. "$top/benchmarks/scaling_scenes.sh"
[ -x "$exe" ] || bash "$top/scripts/build.sh"

variant_settings() { # variant -> prm lines appended at the end (later entries win)
  case $1 in
    seed) printf 'subsection Quadrature\n  set Cut cells = gauss\n  set Gauss points in cut cells = 7\nend\n' ;;
    levelset) printf 'subsection Quadrature\n  set Cut cells = level set\nend\n' ;;
    adaptive) printf 'subsection Quadrature\n  set Cut cells = gauss\n  set Gauss points in cut cells = 7\nend\nsubsection Refinement\n  set Particle refinement levels = 2\nend\n' ;;
    rampold) variant_settings adaptls
             printf 'subsection Multiplier\n  set Interior pressure penalty = 1\nend\n' ;;
    *old) variant_settings "${1%old}"
          printf 'subsection Multiplier\n  set Penalty ramp = 0\n  set Strain penalty = 0.05\n  set Interior pressure penalty = 1\nend\n' ;;
    *it) variant_settings "${1%it}"
         printf 'subsection Solver\n  set Linear solver = iterative\nend\n' ;;
    long) variant_settings seed ;;  # the seed variant continued to t = 1000 (doc/stability.md)
    adaptls) adaptive_levelset ;;
    *) echo "unknown variant $1" >&2; exit 2 ;;
  esac
}

run() { # scene variant end_time
  local scene=$1 variant=$2 end=$3 dir="$work/$1_$2"
  local prm="$dir.prm"
  # The long run starts from the seed variant's last checkpoint when there is one.
  if [ "$variant" = long ] && [ ! -d "$dir" ] && [ -d "$work/$1_seed/checkpoint" ]; then
    cp -r "$work/$1_seed" "$dir"; cp "$work/$1_seed.log" "$dir.log"
  fi
  {
    sed -e "s#^\(\s*set Directory\s*=\).*#\1 $dir#" -e "s/^\(\s*set End time\s*=\).*/\1 $end/" \
        -e "s/^\(\s*set VTU interval\s*=\).*/\1 0/" "$top/prm/$scene.prm"
    variant_settings "$variant"
    local resume=false
    [ -f "$dir/checkpoint/state.txt" ] || [ -f "$dir/checkpoint.old/state.txt" ] && resume=true
    printf 'subsection Checkpointing\n  set Interval = 20\n  set Resume = %s\nend\n' "$resume"
  } > "$prm"
  echo "$(date +%T) $scene/$variant to t = $end (log $dir.log)"
  bash "$top/scripts/mpirun.sh" "${RANKS:-1}" "$exe" "$prm" >> "$dir.log" 2>&1
  echo "$(date +%T) $scene/$variant: exit $?"
}

for spec in "$@"; do
  [ "$spec" = --report ] && continue
  IFS=: read -r scene variant end <<< "$spec"
  run "$scene" "$variant" "$end"
done

# ---- Report --------------------------------------------------------------------------
# One row per run of the work directory. The rows of runs it does not hold stay as the
# table had them, so that running one scene in a new work directory keeps the others.
csv="$top/doc/smoothness${TAG:+_$TAG}.csv"
rows=$(mktemp)
for dir in "$work"/*_*/; do
  dir=${dir%/}; name=$(basename "$dir"); scene=${name%%_*}; variant=${name#*_}
  [ -f "$dir/statistics.csv" ] || continue
  end=$(sed -n 's/^\s*set End time\s*=\s*//p' "$dir.prm" | tail -1)
  awk -F, -v scene="$scene" -v variant="$variant" -v end="$end" -v sfile="$dir/smoothness.csv" '
    NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i; next }  # columns by name
    { n++; t = $col["time"]; w += $col["wall_seconds"]; it += $col["nonlinear_iterations"]
      h += $col["time_step_reductions"]; if (n == 1) d0 = $col["dofs"]; d1 = $col["dofs"] }
    END {
      s = "";
      if ((getline line < sfile) > 0 && (getline line < sfile) > 0) { split(line, f, ","); s = f[2] }
      complete = (t >= end - 1e-9) ? "yes" : "partial";
      if (complete != "yes") s = "";   # the meter writes only at the end of a run
      printf "%s,%s,%g,%d,%s,%s,%.0f,%d,%d,%.2f,%d\n", scene, variant, t, n, complete, s, w, d0, d1, it / n, h
    }' "$dir/statistics.csv" >> "$rows"
done
{
  echo "scene,variant,t_end,steps,complete,smoothness,wall_seconds,dofs_first,dofs_last,newton_per_step,time_step_reductions"
  { [ -f "$csv" ] && awk -F, 'NR == FNR { run[$1 "," $2]; next }
                              FNR > 1 && !(($1 "," $2) in run)' "$rows" "$csv"
    cat "$rows"; } | LC_ALL=C sort -t, -k1,1 -k2,2
} > "$rows.table" && mv "$rows.table" "$csv"
rm -f "$rows"
column -s, -t "$csv"

plot() { # scene column label
  local scene=$1 col=$2 label=$3 png="$top/doc/smoothness_$1${TAG:+_$TAG}.png" cmd=""
  for dir in "$work/${scene}"_*/; do
    dir=${dir%/}; [ -f "$dir/particles.csv" ] || continue
    [ "${dir##*_}" = long ] && continue
    cmd+="${cmd:+, }'$dir/particles.csv' using 1:$col with lines title '$(basename "$dir" | sed 's/^[^_]*_//')'"
  done
  [ -n "$cmd" ] || return 0
  # A figure shows every run of its scene in the table, or stays as it is.
  local missing
  missing=$(awk -F, -v scene="$scene" 'NR > 1 && $1 == scene && $2 != "long" { print $2 }' "$csv" |
            while read -r v; do [ -f "$work/${scene}_$v/particles.csv" ] || printf '%s ' "$v"; done)
  if [ -n "$missing" ]; then
    echo "kept $png: the work directory has no runs $missing"
    return 0
  fi
  gnuplot -e "set terminal pngcairo size 900,500; set output '$png'; set datafile separator ',';
              set key autotitle columnhead; set xlabel 't'; set ylabel '$label';
              set title '$scene: $label of the particle'; set grid; plot $cmd" &&
    echo "wrote $png"
}
plot sediment 7 'V_y'
plot sediment2d 7 'V_y'
plot cavity2d 6 'V_x'
# The long run (doc/stability.md): height and velocity of the sphere to t = 1000.
long="$work/sediment_long/particles.csv"
[ -f "$long" ] && gnuplot -e "set terminal pngcairo size 900,600; set output '$top/doc/sediment_3d_long.png';
  set datafile separator ','; set multiplot layout 2,1; set grid; set xlabel 't';
  set ylabel 'y'; plot '$long' using 1:4 every ::1 with lines notitle;
  set ylabel 'V_y'; plot '$long' using 1:7 every ::1 with lines notitle; unset multiplot" &&
  echo "wrote $top/doc/sediment_3d_long.png"
plot cavity 6 'V_x'
