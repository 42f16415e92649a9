"""Seed §3.4: started from p = 0, one solve returns rest and the hydrostatic pressure.
Requirement: |u|, |V|, |omega| <= 1e-10 and the pressure equal to rho_f g.(x - x_ref) (RMS
deviation <= 1e-10, relative to a hydrostatic pressure range of 20)."""
import sys
from testlib import table, check, finish

out = sys.argv[1]
stats = table(out, "statistics.csv")
check(stats[0]["initial_residual"] > 1e-3, "the start is far from the solution (p = 0)")
for row in stats:
    s = int(row["step"])
    check(row["residual"] <= 1e-10, f"step {s}: final residual {row['residual']:.3e} <= 1e-10")
    check(row["max_velocity"] <= 1e-10, f"step {s}: max |u| = {row['max_velocity']:.3e} <= 1e-10")
    check(row["hydrostatic_deviation"] <= 1e-10,
          f"step {s}: RMS(p - p_hydrostatic) = {row['hydrostatic_deviation']:.3e} <= 1e-10")
for row in table(out, "particles.csv"):
    v = max(abs(row[c]) for c in ("vx", "vy", "vz"))
    w = max(abs(row[c]) for c in ("wx", "wy", "wz"))
    check(v <= 1e-10 and w <= 1e-10, f"t = {row['time']}: |V| = {v:.2e}, |omega| = {w:.2e} <= 1e-10")
finish()
