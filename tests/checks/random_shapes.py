"""Ellipses placed at random, settling with collisions (tests/random_ellipses_2d.prm).

The expected ellipses are read from the scene's own parameters.prm: Random
particles/Count ellipses of the semi-axis ratio of Shape, the largest semi-axis (the
radius column of particles.csv) in the Radius range, the a axis at the angle rotz. Each
ellipse's boundary is sampled densely here (2000 points; the sampled distance of two
boundaries exceeds the true one by less than 1e-6 at these sizes; 400 after t = 0), so
the gaps are not the program's: at t = 0 they must keep the minimum gap to each other and to the walls
(the walls by the exact extent of a turned ellipse), and some pairs must be closer than
their bounding balls would allow (the placement uses the true gap); at every step no
two overlap."""
import math
import sys
import numpy as np
from testlib import table, parameters, check, finish

out = sys.argv[1]
prm = parameters(out)
rows = table(out, "particles.csv")
lower = [float(v) for v in prm["Geometry/Lower corner"].split(",")]
upper = [float(v) for v in prm["Geometry/Upper corner"].split(",")]
count = int(prm["Particles/Random particles/Count"])
word, *ratios = prm["Particles/Random particles/Shape"].replace(",", " ").split()
ratio = min(float(v) for v in ratios) / max(float(v) for v in ratios)
r_min, r_max = (float(v) for v in prm["Particles/Random particles/Radius"].split(","))
gap = float(prm["Particles/Random particles/Minimum gap"])
sub_y = float(prm["Particles/Random particles/Lower corner"].split(",")[1])
# rotz is the angle of the axis given first; Shape gives the longer one first here.
check(word == "ellipse" and float(ratios[0]) > float(ratios[1]), "the scene asks for ellipses, a > b")

times = sorted({r["time"] for r in rows})
steps = [[r for r in rows if r["time"] == t] for t in times]
check(all(len(s) == count for s in steps), f"{count} ellipses in each of the {len(steps)} rows")
first = steps[0]


def boundary(r, n=2000):
    a, b, t = r["radius"], ratio * r["radius"], r["rotz"]
    s = np.linspace(0, 2 * math.pi, n, endpoint=False)
    x, y = a * np.cos(s), b * np.sin(s)
    return np.stack([r["x"] + math.cos(t) * x - math.sin(t) * y,
                     r["y"] + math.sin(t) * x + math.cos(t) * y], axis=1)


def extents(r):
    """Half widths of the turned ellipse along x and y."""
    a, b, t = r["radius"], ratio * r["radius"], r["rotz"]
    return (math.sqrt((a * math.cos(t)) ** 2 + (b * math.sin(t)) ** 2),
            math.sqrt((a * math.sin(t)) ** 2 + (b * math.cos(t)) ** 2))


def gaps(step, n=2000):
    """Sampled boundary distance (n points each) of every pair whose bounding balls come
    within 2 gap, and how many of those bounding balls are closer than gap."""
    result, closer = [], 0
    pts = [boundary(r, n) for r in step]
    for i in range(len(step)):
        for j in range(i + 1, len(step)):
            a, b = step[i], step[j]
            ball = math.hypot(a["x"] - b["x"], a["y"] - b["y"]) - a["radius"] - b["radius"]
            if ball >= 2 * gap:
                result.append(ball)
                continue
            closer += ball < gap
            d = pts[i][:, None, :] - pts[j][None, :, :]
            result.append(float(np.sqrt((d ** 2).sum(axis=2)).min()))
    return result, closer


check(all(r_min <= r["radius"] <= r_max for r in first), "largest semi-axes in the given range")
angles = sorted(math.fmod(r["rotz"], math.pi) % math.pi for r in first)
widest = max([b - a for a, b in zip(angles, angles[1:])] + [angles[0] + math.pi - angles[-1]])
check(widest < math.pi / 2, f"orientations spread over all angles: widest empty arc {widest:.2f} rad")
check(all(r["y"] - extents(r)[1] >= sub_y for r in first), "ellipses inside the sub-box")
check(all(min(r["x"] - extents(r)[0] - lower[0], upper[0] - r["x"] - extents(r)[0],
              upper[1] - r["y"] - extents(r)[1]) >= gap * (1 - 1e-6) for r in first),
      "ellipses at least the minimum gap from the walls (their true extents)")
initial, closer = gaps(first)
check(min(initial) >= gap - 1e-6, f"ellipses start at least the minimum gap apart: {min(initial):.5f}")
check(closer > 0, f"the placement keeps the true gap: {closer} pairs of bounding balls closer than it")
smallest = min(min(gaps(s, 400)[0]) for s in steps)
check(smallest > 0, f"no two ellipses ever overlap: smallest gap {smallest:.4f}")
check(any(r["contact_fx"] != 0 or r["contact_fy"] != 0 for r in rows if r["time"] > 0),
      "the repulsion acts")
mean_drop = sum(a["y"] - b["y"] for a, b in zip(first, steps[-1])) / count
check(mean_drop > 0, f"the ellipses settle: mean drop {mean_drop:.4f}")
check(any(abs(a["rotz"] - b["rotz"]) > 1e-6 for a, b in zip(first, steps[-1])), "they turn")
finish()
