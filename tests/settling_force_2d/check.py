"""Terminal settling: the force from lambda balances the particle's weight rho_P |P| g
(formulation.md, 'Summing 1 and 4-5 cancels lambda'). Analytic limit, no fit."""
import math
import sys
from testlib import table, check, finish

rows = table(sys.argv[1], "particles.csv")
weight = 1.5 * math.pi * 0.1**2 * 10.0
last = rows[-5:]
check(all(r["vy"] < -0.003 for r in last), "the disk falls (vy < -0.003 over the last 5 steps)")
vy = [r["vy"] for r in last]
check((max(vy) - min(vy)) / abs(sum(vy) / len(vy)) < 0.05, f"vy is steady within 5 %: {vy}")
mean_fy = sum(r["fy"] for r in last) / len(last)
check(abs(mean_fy / weight - 1) < 0.005,
      f"mean F_y over the last 5 steps {mean_fy:.6f} = rho_P|P|g = {weight:.6f} within 0.5 %")
for r in last:
    check(abs(r["fy"] / weight - 1) < 0.01, f"t = {r['time']}: F_y = {r['fy']:.6f} within 1 %")
    check(abs(r["fx"]) < 1e-3 * weight, f"t = {r['time']}: F_x = {r['fx']:.2e} ~ 0 (symmetry)")
finish()
