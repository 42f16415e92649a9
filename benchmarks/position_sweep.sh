#!/usr/bin/env bash
# Diagnosis of velocity steps: the hydrodynamic force on a disk as a function of its position.
# A disk (R = 0.2) with prescribed velocity (0, -0.012) in a Stokes fluid, one BDF1 step of
# 0.1 from rest on a uniform 32 x 64 mesh (h = 1/32), level-set quadrature, is placed at
# (0.05, 1 - s h) for s = 0, 0.02, ..., 2. Everything that the step sees depends on s only
# through the geometry, so F_y(s) shows directly whether the discrete problem changes
# continuously as the disk moves across the mesh, and which cell events cause the steps
# (a cell starting or stopping to be cut, a cut cell becoming inside or the reverse).
# Variants: no_ramp (Penalty ramp 0, Strain penalty 0.05, Interior pressure penalty
# delta = 1), ramp_delta1 (ramp 0.2, s_e 0.15, delta = 1), default (ramp 0.2, s_e 0.15,
# delta = 1e-3) and agglomerated (the defaults with Quadrature/Pressure agglomeration =
# 0.25).
# Writes doc/position_sweep.csv (s, F_y per variant), doc/position_sweep.png and prints the
# RMS of the second difference of F_y over s (0 for a smooth curve sampled finely).
# Usage: bash benchmarks/position_sweep.sh        (~6 min on 2 cores; finished runs in
#        benchmarks/work/position_sweep are reused)
set -uo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
exe="${EXE:-$top/build/fdparticle}"
work="${WORK:-$top/benchmarks/work/position_sweep}"
[ -x "$exe" ] || bash "$top/scripts/build.sh"
mkdir -p "$work"

settings() {
  case $1 in
    no_ramp) printf 'subsection Multiplier\n  set Penalty ramp = 0\n  set Strain penalty = 0.05\n  set Interior pressure penalty = 1\nend\n' ;;
    ramp_delta1) printf 'subsection Multiplier\n  set Interior pressure penalty = 1\nend\n' ;;
    default) ;;
    agglomerated) printf 'subsection Quadrature\n  set Pressure agglomeration = 0.25\nend\n' ;;
  esac
}

one() { # variant index
  local v=$1 i=$2 d="$work/$1/$2"
  # Runs already done are kept (delete the work directory to redo them).
  [ "$(wc -l < "$d/out/particles.csv" 2>/dev/null)" = 2 ] && return 0
  mkdir -p "$d"
  local y; y=$(awk -v i="$i" 'BEGIN { printf "%.12f", 1 - i / 50 / 32 }')
  {
    cat <<EOF
set Dimension = 2
set Gravity = 0, -10
subsection Geometry
  set Lower corner = -0.5, -0.5
  set Upper corner = 0.5, 1.5
  set Subdivisions = 32, 64
end
subsection Fluid
  set Convection = false
end
subsection Particles
  set Particles = 0.05, $y : 0.2 : 1.5 : prescribed : 0, -0.012
end
subsection Quadrature
  set Cut cells = level set
end
subsection Time
  set Time step = 0.1
  set End time  = 0.1
  set Scheme    = BDF1
end
subsection Output
  set VTU interval = 0
  set Directory = $d/out
end
EOF
    settings "$v"
  } > "$d/run.prm"
  "$exe" "$d/run.prm" > "$d/log" 2>&1 || { echo "run $v/$i failed (see $d/log)" >&2; return 1; }
}
export -f one settings
export exe work

variants="no_ramp ramp_delta1 default agglomerated"
for v in $variants; do
  seq 0 100 | xargs -P 2 -I{} bash -c "one $v {}"
done

csv="$top/doc/position_sweep.csv"
{
  echo "s,$(echo $variants | tr ' ' ',')"
  for i in $(seq 0 100); do
    line=$(awk -v i="$i" 'BEGIN { printf "%g", i / 50 }')
    for v in $variants; do
      line+=",$(tail -1 "$work/$v/$i/out/particles.csv" | cut -d, -f13)"
    done
    echo "$line"
  done
} > "$csv"
/usr/bin/python3 - "$csv" <<'EOF'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
for v in list(rows[0])[1:]:
    f = [float(r[v]) for r in rows]
    d2 = [f[i + 1] - 2 * f[i] + f[i - 1] for i in range(1, len(f) - 1)]
    rms = (sum(x * x for x in d2) / len(d2)) ** 0.5
    print(f"{v:9s} mean F_y {sum(f) / len(f):.5f}  RMS second difference {rms:.2e} "
          f"({rms / (sum(f) / len(f)):.1e} relative)  max |d2| {max(map(abs, d2)):.2e}")
EOF
gnuplot -e "set terminal pngcairo size 900,500 noenhanced; set output '$top/doc/position_sweep.png';
  set datafile separator ','; set key autotitle columnhead; set grid;
  set xlabel 'disk centre moved down by s cells'; set ylabel 'F_y after one step';
  set title 'Force on a disk against its position on a 32 x 64 mesh (benchmarks/position_sweep.sh)';
  plot '$csv' using 1:2 with linespoints, '' using 1:3 with linespoints, '' using 1:4 with linespoints,
       '' using 1:5 with linespoints" &&
  echo "wrote $csv and doc/position_sweep.png"
