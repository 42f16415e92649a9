#!/usr/bin/env bash
# The extreme scenes of doc/stability.md (tests/stability_*.prm, wall_rest_2d, plus the runs too
# long for ctest: high Reynolds number and the 2D sediment scene to t = 1000), one after the
# other on one rank. Writes doc/stability.csv (one row per scene: steps, wall seconds per
# step, Newton iterations per step, time-step halvings, final particle state, exit status).
# Regenerate with:
#   bash benchmarks/stability.sh
set -uo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
exe="$top/build/fdparticle"
[ -x "$exe" ] || bash "$top/scripts/build.sh"
work="$(mktemp -d)"
out="$top/doc/stability.csv"
echo "scene,exit,steps,seconds_per_step,newton_per_step,halvings,t_end,y,vy,fy,contact_fy" > "$out"
run() { # name prm-file
  local name=$1 prm=$2
  sed -e '/^# test-/d' "$prm" > "$work/$name.prm"
  printf 'subsection Output\n  set Directory = %s\n  set VTU interval = 0\nend\n' "$work/$name" >> "$work/$name.prm"
  "$exe" "$work/$name.prm" > "$work/$name.log" 2>&1; local status=$?
  local s="$work/$name/statistics.csv" p="$work/$name/particles.csv"
  local agg; agg=$(awk -F, 'NR>1{n++; w+=$8; it+=$6; h+=$13} END{if(n) printf "%d,%.4g,%.3g,%d", n, w/n, it/n, h; else printf "0,,,"}' "$s" 2>/dev/null)
  local fin; fin=$(tail -1 "$p" 2>/dev/null | awk -F, '{printf "%s,%s,%s,%s,%s", $1, $4, $7, $13, $19}')
  echo "$name,$status,$agg,$fin" >> "$out"
  echo "$name: exit $status; $(grep -m1 'error' "$work/$name.log" | cut -c1-200)"
}
for prm in "$top"/tests/stability_*.prm "$top/tests/wall_rest_2d.prm"; do
  run "$(basename "$prm" .prm)" "$prm"
done
# Reynolds number ~ 100-1000: the sediment 2D scene with mu = 1e-4 on the seed's mesh and
# on a 4x finer one.
for sub in "8, 16" "32, 64"; do
  sed -e "s/set Viscosity  = 1/set Viscosity  = 1e-4/" -e "s/set Subdivisions        = 8, 16/set Subdivisions        = $sub/" \
      -e "s/set End time  = 12/set End time  = 5/" "$top/prm/sediment2d.prm" > "$work/re.prm"
  run "high_re_${sub/, /x}" "$work/re.prm"
done
# Very long run: the 2D sediment scene to t = 1000 (the disk settles and rests on the floor).
sed -e "s/set End time  = 12/set End time  = 1000/" "$top/prm/sediment2d.prm" > "$work/long.prm"
run long_2d "$work/long.prm"
rm -rf "$work"
column -s, -t "$out"
