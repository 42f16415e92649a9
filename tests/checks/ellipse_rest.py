"""An ellipse at rest on the floor (tests/ellipse_floor_2d.prm).

At rest on a flat wall a convex body is in equilibrium where the wall's force passes
through its centre: an ellipse on its broad side (stable) or on its tip (unstable); it must
end on the broad side. The wall repulsion F = K (1 - g/rho)^2, K = 100 W, acts at the gap g
of the ellipse's lowest point, so the rest gap is g = rho (1 - sqrt(W/K)) = 0.9 rho
(Glowinski et al., J. Comput. Phys. 169 (2001), eq. 2.7, as tests/wall_rest_2d.prm for a
disk) and the contact force is the apparent weight W = (rho_P - rho_f) pi a b g. The
lowest point of an ellipse whose a axis is at angle theta is
sqrt(a^2 sin^2 theta + b^2 cos^2 theta) below its centre: it never reaches the floor."""
import math
import sys
from testlib import table, check, finish, parameters

out = sys.argv[1]
prm = parameters(out)
rows = table(out, "particles.csv")
a, b = 0.2, 0.1
floor = float(prm["Geometry/Lower corner"].split(",")[1])
levels = int(prm["Refinement/Particle refinement levels"])
h = 0.125 / 2 ** levels  # the finest cell: 8 x 16 base cells of 0.125
W = (5 - 1) * math.pi * a * b * 10


def lowest_gap(r):
    theta = r["rotz"]
    return r["y"] - floor - math.sqrt((a * math.sin(theta)) ** 2 + (b * math.cos(theta)) ** 2)


last = rows[-1]
theta = math.remainder(last["rotz"], math.pi)  # the broad side down: theta = 0 or pi
check(min(lowest_gap(r) for r in rows) > 0, "the ellipse never touches the floor")
check(abs(theta) < 1e-4, f"at rest on its broad side: angle {theta:.2e} rad (mod pi)")
check(abs(lowest_gap(last) / (0.9 * h) - 1) < 1e-5,
      f"rest gap {lowest_gap(last):.8f} = 0.9 h = {0.9 * h:.8f} (1e-5)")
check(abs(last["vy"]) < 1e-8 and abs(last["wz"]) < 1e-6,
      f"at rest: vy = {last['vy']:.1e}, wz = {last['wz']:.1e}")
check(abs(last["contact_fy"] / W - 1) < 1e-5,
      f"the contact force {last['contact_fy']:.8f} carries the apparent weight {W:.8f} (1e-5)")
finish()
