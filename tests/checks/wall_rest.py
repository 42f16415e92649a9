"""A disk at rest on the floor under the wall repulsion (tests/wall_rest_2d.prm).

Analytic equilibrium of F = K (1 - g/rho)^2 = W with K = 100 W: g = 0.9 rho, rho = h =
0.125 (Glowinski et al. 2001 form, our defaults). At rest the hydrodynamic force is the
buoyancy rho_f |P| |g| (hydrostatics). That the repulsion then carries the apparent weight
is the particle's own equation at rest, which the code solves, so it is not checked
separately: the rest gap checks the repulsion law."""
import math
import sys
from testlib import table, check, finish

rows = table(sys.argv[1], "particles.csv")
R, rho_f, g = 0.2, 1.0, 10.0
area = math.pi * R * R
last = rows[-1]
gap = last["y"] - R - (-0.5)
check(min(r["y"] - R + 0.5 for r in rows) > 0, "the disk never touches the floor")
check(abs(gap - 0.9 * 0.125) < 1e-6, f"rest gap {gap:.8f} = 0.9 h = 0.1125 (1e-6)")
check(abs(last["vy"]) < 1e-8, f"at rest: vy = {last['vy']:.2e}")
check(abs(last["fy"] / (rho_f * area * g) - 1) < 1e-4,
      f"hydrodynamic force {last['fy']:.8f} = buoyancy {rho_f * area * g:.8f} (1e-4 relative)")
check(all(r["contact_fy"] == 0 for r in rows if r["y"] - R + 0.5 >= 0.125),
      "no repulsion while the gap exceeds the range")
finish()
