"""Terminal settling velocity of a disk midway between two walls against Faxen's drag
(see tests/settling_force_2d.prm for the formula and its source)."""
import math
import sys
from testlib import table, check, finish, parameters

out = sys.argv[1]
prm = parameters(out)
rows = table(out, "particles.csv")
centre, radius, rho_p = prm["Particles/Particles"].split(":")
radius, rho_p = float(radius), float(rho_p)
mu, rho_f = float(prm["Fluid/Viscosity"]), float(prm["Fluid/Density"])
g = -float(prm["Gravity"].split(",")[1])
half_width = (float(prm["Geometry/Upper corner"].split(",")[0]) -
              float(prm["Geometry/Lower corner"].split(",")[0])) / 2
k = radius / half_width
drag = 4 * math.pi * mu / (math.log(1 / k) - 0.9157 + 1.7244 * k**2 - 1.7302 * k**4 +
                           2.4056 * k**6 - 4.5913 * k**8)
u_faxen = (rho_p - rho_f) * math.pi * radius**2 * g / drag
vy = [-r["vy"] for r in rows[-2:]]
check(abs(vy[1] - vy[0]) < 2e-3 * vy[1], f"the disk has reached its terminal velocity: {vy}")
check(abs(vy[-1] / u_faxen - 1) < 0.015,
      f"terminal velocity {vy[-1]:.7f} = Faxen's {u_faxen:.7f} within 1.5 % "
      f"({100 * (vy[-1] / u_faxen - 1):+.2f} %)")
finish()
