#!/usr/bin/env bash
# OpenBLAS's kernels (doc/performance.md, "The BLAS kernels"): the kernels fdparticle runs
# with (`fdparticle --version`: OpenBLAS's own choice, or SkylakeX / Haswell where OpenBLAS
# fell back to its Prescott kernels on a CPU it does not know, BlasKernels) against the
# Prescott kernels (OPENBLAS_CORETYPE=Prescott), on one rank:
#   dgemm       numpy's product of two 3000 x 3000 matrices (the same libblas.so.3)
#   sediment    prm/sediment.prm, 3 steps (direct solver, 61 k unknowns)
#   sediment12  the 3D sediment step of benchmarks/scaling_scenes.sh at n = 12 (direct, 198 k)
#   sediment16  the same at n = 16 (iterative solver with its cut-cell patch, 457 k)
#   cavity2d    prm/cavity2d.prm to t = 0.1 (direct, 2D)
# Each scene runs REPEAT times (default 2) with both kernels in alternation. Writes
# doc/blas_kernels.csv, one row per run: the scene, the kernels, the repetition, the
# unknowns, the steps' wall time (statistics.csv's wall_seconds summed: without the
# start-up), the "solve" and "assemble system" sections of the run's timer, the run's wall
# time and peak memory, then the date and the commit; for dgemm its GFlop/s in the steps'
# column. Usage: [SCENES="dgemm sediment sediment12 sediment16 cavity2d"] [REPEAT=2]
#        bash benchmarks/blas_kernels.sh   (~6 min; alone on the machine)
set -uo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
exe="${EXE:-$top/build/fdparticle}"
work="${WORK:-$top/benchmarks/work/blas_kernels}"
scenes="${SCENES:-dgemm sediment sediment12 sediment16 cavity2d}"
repeat="${REPEAT:-2}"
[ -x "$exe" ] || bash "$top/scripts/build.sh"
mkdir -p "$work"
. "$top/benchmarks/scaling_scenes.sh"
csv="$top/doc/blas_kernels.csv"
date=$(date -u +%Y-%m-%d); commit=$(git -C "$top" rev-parse --short HEAD)
# "BLAS: OpenBLAS 0.3.21, SkylakeX kernels (...)" -> SkylakeX
chosen=$(env -u OPENBLAS_CORETYPE "$exe" --version | sed -n 's/^BLAS: [^,]*, \([A-Za-z0-9]*\) kernels.*/\1/p')
[ -n "$chosen" ] || { echo "the BLAS is not OpenBLAS: nothing to compare"; exit 1; }

scene() { # name directory -> prm on stdout
  case $1 in
    sediment)   sed -e 's/^ *set End time .*/  set End time = 0.3/' "$top/prm/sediment.prm" ;;
    sediment12) sediment 12; printf 'subsection Solver\n  set Linear solver = direct\nend\n' ;;
    sediment16) sediment 16; printf 'subsection Solver\n  set Linear solver = iterative\nend\n' ;;
    cavity2d)   sed -e 's/^ *set End time .*/  set End time = 0.1/' "$top/prm/cavity2d.prm" ;;
  esac
  printf 'subsection Output\n  set Directory = %s\n  set VTU interval = 0\nend\n' "$2"
}

section() { # log name -> seconds of the timer's section
  awk -F'|' -v s="$2" '{ n = $2; gsub(/^ +| +$/, "", n) } n == s { t = $4; gsub(/[ s]/, "", t); print t }' "$1"
}

echo "scene,kernels,repetition,dofs,step_seconds,solve_seconds,assembly_seconds,run_seconds,peak_mb,date,commit" > "$csv"
for name in $scenes; do
  for k in $(seq "$repeat"); do
    for kernels in "$chosen" Prescott; do
      if [ "$name" = dgemm ]; then
        rate=$(OPENBLAS_CORETYPE=$kernels /usr/bin/python3 -c '
import numpy, time
a = numpy.random.rand(3000, 3000); b = numpy.random.rand(3000, 3000); a @ b
t = time.perf_counter(); a @ b; print("%.1f" % (2 * 3000**3 / (time.perf_counter() - t) / 1e9))')
        echo "dgemm,$kernels,$k,0,$rate,,,,,$date,$commit" | tee -a "$csv"
        continue
      fi
      d="$work/$name-$kernels-$k"
      rm -rf "$d"; mkdir -p "$d"
      scene "$name" "$d/out" > "$d/scene.prm"
      if ! OPENBLAS_CORETYPE=$kernels /usr/bin/time -f "%e %M" -o "$d/time" \
           bash "$top/scripts/mpirun.sh" 1 "$exe" "$d/scene.prm" > "$d/log" 2>&1; then
        echo "$name ($kernels) failed (see $d/log)"
        continue
      fi
      read -r seconds kb < "$d/time"
      steps=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i; next }
                       { s += $col["wall_seconds"]; dofs = $col["dofs"] }
                       END { printf "%d,%.2f", dofs, s }' "$d/out/statistics.csv")
      echo "$name,$kernels,$k,$steps,$(section "$d/log" solve),$(section "$d/log" "assemble system"),$seconds,$((kb / 1024)),$date,$commit" | tee -a "$csv"
    done
  done
done
