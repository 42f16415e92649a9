"""A disk dragged by a sliding floor through Coulomb friction (tests/wall_friction_2d.prm).

Computed here from particles.csv: the contact force split into its normal (y) and
tangential (x) parts, and the velocity of the disk's surface at the contact point, which
ContactFriction puts in the middle of the gap: V_x + omega_z (R + gap/2). Coulomb's law
bounds |F_t| by the coefficient times F_n and saturates the bound while the surfaces
slide; the friction then stops the sliding (the disk rolls on the floor), and its torque
spins the disk anticlockwise."""
import sys
from testlib import table, parameters, check, finish

out = sys.argv[1]
prm = parameters(out)
rows = table(out, "particles.csv")
mu = float(prm["Wall repulsion/Friction coefficient"])
floor = 1.0
R = 0.1


def surface_velocity(r):
    gap = r["y"] - R
    return r["vx"] + r["wz"] * (R + gap / 2)


touching = [r for r in rows if r["contact_fy"] > 0]
check(len(touching) == len(rows) - 1, f"the disk rests on the floor at every step "
      f"({len(touching)} of {len(rows) - 1})")
excess = max(abs(r["contact_fx"]) - mu * r["contact_fy"] for r in touching)
check(excess <= 1e-9, f"|F_t| <= {mu} F_n at every step (largest excess {excess:.2e})")
early = [r for r in touching if r["time"] <= 0.05]
sliding = min(r["contact_fx"] / r["contact_fy"] for r in early)
check(sliding > 0.99 * mu and all(surface_velocity(r) < 0.9 * floor for r in early),
      f"while the floor slides under the disk the friction is {mu} F_n, forward "
      f"(smallest ratio {sliding:.4f})")
last = rows[-1]
check(abs(surface_velocity(last) - floor) < 0.01 * floor,
      f"the disk ends rolling on the floor: its surface moves at {surface_velocity(last):.5f}")
check(last["vx"] > 0.1 and last["wz"] > 1,
      f"dragged forward (vx {last['vx']:.4f}) and spun anticlockwise (wz {last['wz']:.4f})")
gaps = [r["y"] - R for r in rows]
check(0 < min(gaps) and max(gaps) < 0.0313,
      f"the disk stays within the contact range of the floor: gap {min(gaps):.5f} to "
      f"{max(gaps):.5f}")
finish()
