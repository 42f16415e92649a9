#!/usr/bin/env bash
# Drafting, kissing and tumbling of two disks (doc/particles.md): runs prm/dkt2d.prm
# (Collisions/Model = repulsion) and, with the argument 'none', the same scene without a
# contact model; then prints the phases (kissing from the first to the last step with the
# gap below the repulsion's range, the time the trailer passes the leader) and plots the
# trajectories and vertical velocities into doc/particles_dkt_2d.png.
#
# Usage (regenerate):  bash benchmarks/dkt_2d.sh [none] [spring-dashpot]
# EXE=PATH overrides the executable, WORK=DIR the work directory; LEVELS=N the particle
# refinement levels (3 by default; another value writes doc/particles_dkt_2d_lN.png).
set -euo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
exe="${EXE:-$top/build/fdparticle}"
levels="${LEVELS:-3}"
work="${WORK:-$top/benchmarks/work/dkt_2d-l$levels}"
png="$top/doc/particles_dkt_2d.png"
[ "$levels" = 3 ] || png="$top/doc/particles_dkt_2d_l$levels.png"
mkdir -p "$work"
models=(repulsion "$@")
for model in "${models[@]}"; do
  sed -e "s|set Model = repulsion|set Model = $model|" \
      -e "s|set Directory    = output/dkt2d|set Directory    = $work/$model|" \
      -e "s|set VTU interval = 10|set VTU interval = 0|" \
      -e "s|set Particle refinement levels = 3|set Particle refinement levels = $levels|" \
      "$top/prm/dkt2d.prm" > "$work/$model.prm"
  /usr/bin/time -f "%e s, %M kB peak" -o "$work/$model.time" "$exe" "$work/$model.prm" \
    > "$work/$model.log" 2>&1 || echo "$model: the run stopped: $(grep -m1 'error' "$work/$model.log")"
  echo "$model: $(cat "$work/$model.time")"
done
/usr/bin/python3 - "$work" "$levels" "${models[@]}" <<'PY'
import csv, math, sys
work, levels, models = sys.argv[1], int(sys.argv[2]), sys.argv[3:]
for model in models:
    rows = list(csv.DictReader(open(f"{work}/{model}/particles.csv")))
    a = [r for r in rows if r["id"] == "0"]; b = [r for r in rows if r["id"] == "1"]
    h = 0.2 / 2 ** levels  # the finest cell edge: 10 x 40 base cells of 0.2
    gap = [math.hypot(float(p["x"]) - float(q["x"]), float(p["y"]) - float(q["y"])) - 0.2
           for p, q in zip(a, b)]
    kiss = [float(a[i]["time"]) for i, g in enumerate(gap) if g < h]
    passed = next((float(p["time"]) for p, q in zip(a, b) if float(p["y"]) < float(q["y"])), None)
    print(f"{model}: ran to t = {float(a[-1]['time']):.2f}; smallest gap {min(gap):.4f}; "
          f"gap below h = {h} from t = {kiss[0] if kiss else float('nan'):.2f} "
          f"to {kiss[-1] if kiss else float('nan'):.2f}; trailer below leader from t = {passed}")
    with open(f"{work}/{model}.dat", "w") as f:
        for p, q in zip(a, b):
            f.write(" ".join(str(v) for v in (p["time"], p["x"], p["y"], p["vy"],
                                              q["x"], q["y"], q["vy"])) + "\n")
PY
gnuplot <<GP
set terminal pngcairo size 1100,500
set output "$png"
set multiplot layout 1,2 title "Two disks, prm/dkt2d.prm (Collisions/Model = repulsion, $levels particle refinement levels)"
set xlabel "t [s]"; set ylabel "y [cm]"; set key bottom left
plot "$work/repulsion.dat" u 1:3 w l lw 2 t "trailer (starts at y = 7.2)", \
     "" u 1:6 w l lw 2 t "leader (starts at y = 6.8)"
set ylabel "v_y [cm/s]"
plot "$work/repulsion.dat" u 1:4 w l lw 2 t "trailer", "" u 1:7 w l lw 2 t "leader"
unset multiplot
GP
echo "wrote ${png#$top/}"
