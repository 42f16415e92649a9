#!/usr/bin/env bash
# The multi-rank tests alone and on a busy machine (doc/parallel_consistency.md, "MPI runs
# on shared cores"): each test of TESTS runs as ctest runs it, first alone, then beside a
# parallel build of the project in another directory and a 2-rank 3D run started with a
# plain mpirun (another user's job: pinned, spinning while it waits), both in a loop.
# Appends one row per test to doc/busy_machine.csv (date, commit, seconds alone and busy,
# their ratio, pass/fail of each) and prints them. Run it with nothing else on the machine.
# Usage: bash benchmarks/busy_machine.sh      (~10 min on 2 cores)
set -uo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
exe="${EXE:-$top/build/fdparticle}"
work="${WORK:-$top/benchmarks/work/busy_machine}"
tests="${TESTS:-bounce_2d mpi_sediment_2d dkt_2d settling_many_2d mpi_cavity_3d}"
[ -x "$exe" ] || bash "$top/scripts/build.sh"
rm -rf "$work"
mkdir -p "$work"
csv="$top/doc/busy_machine.csv"
[ -f "$csv" ] || echo "date,commit,test,alone_seconds,busy_seconds,ratio,alone,busy" > "$csv"
commit=$(git -C "$top" rev-parse --short HEAD 2>/dev/null || echo unknown)
[ -z "$(git -C "$top" status --porcelain 2>/dev/null)" ] || commit="$commit+"

run_tests() { # label: seconds and result of each test to $work/LABEL.txt
  for t in $tests; do
    start=$(date +%s.%N)
    if python3 "$top/tests/run_test.py" --executable "$exe" --prm "$top/tests/$t.prm" \
         --work "$work/$1-$t" > "$work/$1-$t.log" 2>&1; then result=pass; else result=fail; fi
    echo "$t $(echo "$(date +%s.%N) - $start" | bc) $result" | tee -a "$work/$1.txt"
  done
}

echo "alone:"
run_tests alone

# The load: its own process group, ended on exit.
git clone -q "$top" "$work/clone"
. "$top/benchmarks/scaling_scenes.sh"
{ sediment 10
  printf 'subsection Solver\n  set Linear solver = iterative\nend\n'
  printf 'subsection Output\n  set Directory = %s\n  set VTU interval = 0\nend\n' "$work/load-out"
} > "$work/load.prm"
setsid bash -c "
  while true; do
    rm -rf '$work/clone/build-load'
    cmake -S '$work/clone' -B '$work/clone/build-load' -G Ninja -DCMAKE_BUILD_TYPE=Release > /dev/null 2>&1
    cmake --build '$work/clone/build-load' -j 2 > /dev/null 2>&1
  done &
  while true; do
    OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 \
      mpirun --oversubscribe -np 2 '$exe' '$work/load.prm' > /dev/null 2>&1
  done &
  wait" &
load=$!
trap 'kill -- -$load 2>/dev/null' EXIT
sleep 30
echo "busy:"
run_tests busy
kill -- -"$load" 2>/dev/null

paste -d' ' "$work/alone.txt" "$work/busy.txt" | while read -r t a ra _ b rb; do
  printf '%s,%s,%s,%.1f,%.1f,%.2f,%s,%s\n' "$(date +%F)" "$commit" "$t" "$a" "$b" \
    "$(echo "$b / $a" | bc -l)" "$ra" "$rb"
done | tee -a "$csv"
