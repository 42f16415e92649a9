#!/usr/bin/env bash
# Time per step of the seed's sediment scene (prm/sediment.prm, 8x16x8, 61k DoFs) on 1 and
# 2 MPI ranks, 3 steps each, in one run so the two are compared on the same machine load.
# Writes doc/time_per_step.csv and prints a Markdown table. Regenerate with:
#   bash benchmarks/time_per_step.sh
set -euo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
exe="$top/build/fdparticle"
[ -x "$exe" ] || bash "$top/scripts/build.sh"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
work="$(mktemp -d)"
out="$top/doc/time_per_step.csv"
echo "ranks,step,newton_iterations,dofs,wall_seconds" > "$out"
for ranks in 1 2; do
  sed -e 's/^ *set End time .*/  set End time = 0.3/' \
      -e "s|^ *set Directory .*|  set Directory = $work/np$ranks|" \
      -e 's/^ *set VTU interval .*/  set VTU interval = 0/' "$top/prm/sediment.prm" > "$work/np$ranks.prm"
  if [ "$ranks" = 1 ]; then "$exe" "$work/np1.prm" > /dev/null
  else bash "$top/scripts/mpirun.sh" "$ranks" "$exe" "$work/np$ranks.prm" > /dev/null; fi
  awk -F, -v r="$ranks" 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
    { print r","$c["step"]","$c["nonlinear_iterations"]","$c["dofs"]","$c["wall_seconds"] }' \
    "$work/np$ranks/statistics.csv" >> "$out"
done
echo "| ranks | mean wall seconds per step | Newton iterations per step |"
echo "|---|---|---|"
awk -F, 'NR>1{s[$1]+=$5; n[$1]++; it[$1]+=$3} END{for (r in s) printf "| %s | %.2f | %.1f |\n", r, s[r]/n[r], it[r]/n[r]}' "$out" | sort
rm -rf "$work"
