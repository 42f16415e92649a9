"""The lubrication correction of prescribed approaches (tests/lubrication_2d.prm).

The expected force is computed here from the centres in particles.csv (the end-of-step
positions, where the code evaluates it): for cylinders the leading lubrication term per
unit length is 3 sqrt(2) pi mu U (a*/g)^(3/2) (a cylinder of radius a* at gap g from a
plane; a* = a1 a2 / (a1 + a2) for two cylinders). The resolved flow carries that term at a
gap widened by s = s_0 (1 - g/g_r), s_0 = 0.033 a* at a wall and 0.85 h between two
cylinders (the 'auto' Gap shift, doc/particles.md; h the finest cell edge), so the
correction is C(g) - C(g + s) below the resolved gap g_r = 3h, zero above."""
import math
import sys
from testlib import table, parameters, check, finish

out = sys.argv[1]
prm = parameters(out)
rows = table(out, "particles.csv")
mu = float(prm["Fluid/Viscosity"])
R, U, h = 0.1, 1.0, 1.0 / 4 / 2 ** 3
g_r = 3 * h


def correction(a_star, g, pair):
    C = lambda x: 3 * math.sqrt(2) * math.pi * mu * (a_star / x) ** 1.5
    s = (0.85 * h if pair else 0.033 * a_star) * (1 - g / g_r)
    return (C(g) - C(g + s)) * U if g < g_r else 0.0


steps = sorted({r["time"] for r in rows if r["time"] > 0})
disk = {k: [r for r in rows if r["id"] == k and r["time"] > 0] for k in (0, 1, 2)}
check(len(steps) == 10 and all(len(v) == len(steps) for v in disk.values()), "10 steps of three disks")
worst, below, above = 0.0, 0, 0
for a, b, c in zip(disk[0], disk[1], disk[2]):
    wall_gap = a["y"] - R
    pair_gap = math.hypot(c["x"] - b["x"], c["y"] - b["y"]) - 2 * R
    for got, expected in ((a["contact_fy"], correction(R, wall_gap, False)),
                          (c["contact_fy"], correction(R / 2, pair_gap, True)),
                          (b["contact_fy"], -correction(R / 2, pair_gap, True))):
        worst = max(worst, abs(got - expected) / max(abs(expected), 1e-3))
    below += wall_gap < g_r
    above += wall_gap >= g_r
check(below >= 3 and above >= 3, f"gaps on both sides of g_r: {above} steps above, {below} below")
check(worst < 1e-8, f"the correction at every step, wall and pair: largest relative difference {worst:.1e}")
check(all(r["contact_fx"] == 0 for r in rows), "no force across the line of approach")
check(disk[0][-1]["contact_fy"] > 0 and disk[2][-1]["contact_fy"] > 0,
      "it opposes the approach (pushes the moving disks back up)")
finish()
