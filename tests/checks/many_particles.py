"""Many particles from a particle file and random placement, settling with collisions
(tests/settling_many_2d.prm).

The expected particles are read here from the scene's own parameters.prm and from the
particle file it names, not from the code: the file's rows must come first with their
values, then Random particles/Count balls with radii in the given range, lying in the
sub-box, at least Minimum gap from each other and from the walls at t = 0. At every step
the gaps are computed from the centres and radii in particles.csv (all pairs): no two
disks may overlap, the collision repulsion must act, and the free disks must settle on
average (one may rise a little in the backflow of the others)."""
import csv
import itertools
import math
import sys
from testlib import table, parameters, check, finish

out = sys.argv[1]
prm = parameters(out)
rows = table(out, "particles.csv")
lower = [float(v) for v in prm["Geometry/Lower corner"].split(",")]
upper = [float(v) for v in prm["Geometry/Upper corner"].split(",")]
with open(prm["Particles/Particle file"]) as f:
    listed = [r for r in csv.reader(line for line in f if not line.startswith("#"))][1:]
count = int(prm["Particles/Random particles/Count"])
r_min, r_max = (float(v) for v in prm["Particles/Random particles/Radius"].split(","))
gap = float(prm["Particles/Random particles/Minimum gap"])
sub_y = float(prm["Particles/Random particles/Lower corner"].split(",")[1])

times = sorted({r["time"] for r in rows})
steps = [[r for r in rows if r["time"] == t] for t in times]
n = len(listed) + count
check(all(len(s) == n for s in steps), f"{n} particles in each of the {len(steps)} rows")
first = steps[0]
check(all(abs(first[k][c] - float(listed[k][i])) == 0 for k in range(len(listed))
          for i, c in enumerate(["x", "y", "radius"])),
      "the particle file's rows come first, with their centres and radii")
fixed = [r for r in rows if r["id"] == 0]
check(all(r["x"] == fixed[0]["x"] and r["y"] == fixed[0]["y"] for r in fixed),
      "the file's fixed particle stays where it is")
random = first[len(listed):]
check(all(r_min <= r["radius"] <= r_max for r in random), "random radii in the given range")
check(all(r["y"] - r["radius"] >= sub_y for r in random), "random balls inside the sub-box")
check(all(min(r["x"] - r["radius"] - lower[0], upper[0] - r["x"] - r["radius"],
              upper[1] - r["y"] - r["radius"]) >= gap * (1 - 1e-9) for r in random),
      "random balls at least the minimum gap from the walls")


def gaps(step):
    return [math.hypot(a["x"] - b["x"], a["y"] - b["y"]) - a["radius"] - b["radius"]
            for a, b in itertools.combinations(step, 2)]


initial = min(g for (a, b), g in zip(itertools.combinations(first, 2), gaps(first))
              if a["id"] >= len(listed) or b["id"] >= len(listed))
check(initial >= gap * (1 - 1e-9), f"random balls start at least the minimum gap apart: {initial:.4f}")
smallest = min(min(gaps(s)) for s in steps)
check(smallest > 0, f"no two disks ever overlap: smallest gap {smallest:.4f}")
check(any(r["contact_fx"] != 0 or r["contact_fy"] != 0 for r in rows if r["time"] > 0),
      "the repulsion acts")
free = range(1, n)
mean_drop = sum(first[k]["y"] - steps[-1][k]["y"] for k in free) / len(free)
check(mean_drop > 0, f"the free disks settle: mean drop {mean_drop:.4f}")
finish()
