"""A disk resting on another resting on the floor (tests/resting_stack_2d.prm).

At rest each disk's forces balance: gravity ρ_s |P| g down, the hydrodynamic force (the
buoyancy ρ_f |P| g up, when the fluid is at rest) and the contact forces. So the floor
carries the apparent weight of both disks, W = (ρ_s − ρ_f) π R² g each, the contact
between the disks the upper one's, and with the repulsion law F = K (1 − gap/h)²,
K = 100 W (doc/method.md §12), the gaps are h (1 − √(F/K)): 0.9 h between the disks and
h (1 − √0.02) above the floor. h is the finest cell edge, 1/8 / 2^2. The values are
computed here from the parameters, not read from the code."""
import math
import sys
from testlib import table, parameters, check, finish

out = sys.argv[1]
prm = parameters(out)
rows = table(out, "particles.csv")
g = abs(float(prm["Gravity"].split(",")[1]))
rho_f = float(prm["Fluid/Density"])
R, rho_s = 0.1, 1.5
W = (rho_s - rho_f) * math.pi * R * R * g
h = 1.0 / 8 / 2 ** 2
bottom = [r for r in rows if r["id"] == 0]
top = [r for r in rows if r["id"] == 1]
b, t = bottom[-1], top[-1]
check(max(abs(b["vy"]), abs(t["vy"])) < 1e-4, f"at rest: |V| = {abs(b['vy']):.2e}, {abs(t['vy']):.2e}")
floor = b["contact_fy"] + t["contact_fy"]
check(abs(floor - 2 * W) < 1e-3 * W, f"the floor carries both apparent weights: {floor:.4f} vs 2W = {2 * W:.4f}")
check(abs(t["contact_fy"] - W) < 1e-3 * W,
      f"the lower disk carries the upper one's: {t['contact_fy']:.4f} vs W = {W:.4f}")
buoyancy = rho_f * math.pi * R * R * g
check(all(abs(r["fy"] - buoyancy) < 1e-3 * W for r in (b, t)),
      f"the hydrodynamic force is the buoyancy {buoyancy:.4f}: {b['fy']:.4f}, {t['fy']:.4f}")
gap_floor = b["y"] - R
gap_pair = t["y"] - b["y"] - 2 * R
check(abs(gap_floor - h * (1 - math.sqrt(0.02))) < 1e-3 * h,
      f"gap above the floor h (1 - sqrt 0.02) = {h * (1 - math.sqrt(0.02)):.5f}: {gap_floor:.5f}")
check(abs(gap_pair - 0.9 * h) < 1e-3 * h, f"gap between the disks 0.9 h = {0.9 * h:.5f}: {gap_pair:.5f}")
drift = max(abs(r["x"] - 0.5) for r in rows)
check(drift < 1e-9, f"nothing drifts sideways: largest |x - 0.5| = {drift:.1e}")
finish()
