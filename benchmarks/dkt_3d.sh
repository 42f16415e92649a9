#!/usr/bin/env bash
# Drafting, kissing and tumbling of two spheres (doc/particles.md, 3D): runs
# prm/dkt3d.prm, prints the phases (the first time the gap drops below the repulsion's
# range, the last time it is below, the time the trailer passes the leader; also in the
# time unit sqrt(d/g) of the published reproductions) and plots heights, vertical
# velocities, the gap and the horizontal distance of the centres into
# doc/particles_dkt_3d.png.
#
# Usage (regenerate):  bash benchmarks/dkt_3d.sh
# EXE=PATH overrides the executable, WORK=DIR the work directory, LEVELS=N the particle
# refinement levels (2 by default, d/h = 4; another value writes
# doc/particles_dkt_3d_lN.png), NP=N runs on N MPI ranks, SOLVER=direct|iterative sets
# Solver/Linear solver (the prm keeps the default, the direct solver; at 3 levels,
# 345 k unknowns, the iterative one needs half the memory: doc/scaling.md); PLOT_ONLY=1 reads the output of an earlier run in WORK/out. The run
# writes a checkpoint every 5 steps; RESUME=1 continues an interrupted run from it.
set -euo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
exe="${EXE:-$top/build/fdparticle}"
levels="${LEVELS:-2}"
np="${NP:-1}"
work="${WORK:-$top/benchmarks/work/dkt_3d-l$levels}"
png="$top/doc/particles_dkt_3d.png"
[ "$levels" = 2 ] || png="$top/doc/particles_dkt_3d_l$levels.png"
mkdir -p "$work"
sed -e "s|set Directory    = output/dkt3d|set Directory    = $work/out|" \
    -e "s|set VTU interval = 10|set VTU interval = 0|" \
    -e "s|set Particle refinement levels = 2|set Particle refinement levels = $levels|" \
    "$top/prm/dkt3d.prm" > "$work/run.prm"
printf 'subsection Checkpointing\n  set Interval = 5\n  set Resume   = %s\nend\n' \
  "$([ "${RESUME:-0}" = 1 ] && echo true || echo false)" >> "$work/run.prm"
# With the iterative solver, 300 cheap iterations in one Krylov basis: at d/h = 8 the cheap
# form needs up to 160 iterations a solve once the pair settles fast (t > 0.07 s), and
# past the default 100 the solve falls back to the inner solve, which made those steps
# 2-3.5 times longer (doc/particles.md).
if [ -n "${SOLVER:-}" ]; then
  printf 'subsection Solver\n  set Linear solver = %s\n' "$SOLVER" >> "$work/run.prm"
  [ "$SOLVER" != iterative ] ||
    printf '  set Cheap iterations = 300\n  set Krylov basis size = 300\n' >> "$work/run.prm"
  printf 'end\n' >> "$work/run.prm"
fi
if [ "${PLOT_ONLY:-0}" != 1 ]; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
  /usr/bin/time -f "%e s, %M kB peak (rank 0)" -o "$work/run.time" \
    bash "$top/scripts/mpirun.sh" "$np" "$exe" "$work/run.prm" > "$work/run.log" 2>&1 ||
    echo "the run stopped: $(grep -m1 -i 'error' "$work/run.log")"
  echo "$np rank(s): $(cat "$work/run.time")"
fi
/usr/bin/python3 - "$work" "$levels" <<'PY'
import csv, math, sys
work, levels = sys.argv[1], int(sys.argv[2])
d, g = 1 / 6, 981.0
unit = math.sqrt(d / g)  # the time unit of the published reproductions
rows = list(csv.DictReader(open(f"{work}/out/particles.csv")))
a = [r for r in rows if r["id"] == "0"]; b = [r for r in rows if r["id"] == "1"]
h = d / 2 ** levels  # the finest cell edge: base cells of edge d
gap = [math.dist([float(p[k]) for k in "xyz"], [float(q[k]) for k in "xyz"]) - d
       for p, q in zip(a, b)]
kiss = [float(a[i]["time"]) for i, s in enumerate(gap) if s < h]
# The coarsest run's range, d/4: the same threshold at every resolution.
quarter = next((float(a[i]["time"]) for i, s in enumerate(gap) if s < d / 4), None)
passed = next((float(p["time"]) for p, q in zip(a, b) if float(q["z"]) < float(p["z"])), None)
fmt = lambda t: "—" if t is None else f"t = {t:.3f} s ({t / unit:.1f} sqrt(d/g))"
print(f"ran to t = {float(a[-1]['time']):.3f} s; smallest gap {min(gap):.4f} "
      f"({min(gap) / h:.2f} h); gap below h = {h:.4f} first at {fmt(kiss[0] if kiss else None)}, "
      f"last at {fmt(kiss[-1] if kiss else None)}; gap below d/4 first at {fmt(quarter)}; "
      f"trailer below leader from {fmt(passed)}")
with open(f"{work}/dkt.dat", "w") as f:
    for p, q, s in zip(a, b, gap):
        across = math.hypot(float(p["x"]) - float(q["x"]), float(p["y"]) - float(q["y"]))
        f.write(" ".join(str(v) for v in (float(p["time"]) / unit, p["z"], p["vz"],
                                          q["z"], q["vz"], s / d, across / d)) + "\n")
PY
gnuplot <<GP
set terminal pngcairo size 1100,800
set output "$png"
set multiplot layout 2,2 title "Two spheres, prm/dkt3d.prm ($levels particle refinement levels, d/h = $((2 ** levels)))"
set xlabel "t (g/d)^{1/2}"; set key bottom left
set ylabel "z [cm]"
plot "$work/dkt.dat" u 1:4 w l lw 2 t "trailer (starts 1.5 d above)", "" u 1:2 w l lw 2 t "leader"
set ylabel "v_z [cm/s]"
plot "$work/dkt.dat" u 1:5 w l lw 2 t "trailer", "" u 1:3 w l lw 2 t "leader"
set ylabel "gap / d"; set key top right
plot "$work/dkt.dat" u 1:6 w l lw 2 t "surface gap", $(/usr/bin/python3 -c "print(1 / 2 ** $levels)") w l dt 2 t "repulsion range (h)"
set ylabel "horizontal distance of the centres / d"; set key top left Left reverse
plot "$work/dkt.dat" u 1:7 w l lw 2 t "the pair turns across the flow (tumbling)"
unset multiplot
GP
echo "wrote ${png#$top/}"
