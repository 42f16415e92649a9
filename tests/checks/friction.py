"""A disk bouncing obliquely off a fixed disk with Coulomb friction (tests/friction_2d.prm).

Computed here from particles.csv: the normal n from the fixed disk's centre to the falling
one's, the contact point in the middle of the gap, the sliding velocity of the falling
disk's surface there along the tangent t (the fixed disk is at rest), and the contact
force split along n and t. Coulomb's law bounds |F_t| by the coefficient times F_n; the
friction opposes the sliding, which it stops within the contact (the disk leaves rolling
on the fixed one), and the torque spins the disk in the sense of that rolling."""
import math
import sys
from testlib import table, parameters, check, finish

out = sys.argv[1]
prm = parameters(out)
rows = table(out, "particles.csv")
mu = float(prm["Collisions/Friction coefficient"])
R = 0.1
disk = [r for r in rows if r["id"] == 0]
fixed = [r for r in rows if r["id"] == 1]


def contact(r, c):
    x, y = r["x"] - c["x"], r["y"] - c["y"]
    d = math.hypot(x, y)
    n, t = (x / d, y / d), (-y / d, x / d)
    arm = R + (d - 2 * R) / 2  # to the middle of the gap
    # V + omega x (-arm n), omega along z
    vx = r["vx"] + r["wz"] * arm * n[1]
    vy = r["vy"] - r["wz"] * arm * n[0]
    F = (r["contact_fx"], r["contact_fy"])
    return (vx * t[0] + vy * t[1], F[0] * n[0] + F[1] * n[1], F[0] * t[0] + F[1] * t[1])


touching = [i for i, r in enumerate(disk) if r["contact_fx"] != 0 or r["contact_fy"] != 0]
check(len(touching) > 2, f"a contact of {len(touching)} steps")
if touching:
    first, last = touching[0], touching[-1]
    before = contact(disk[first - 1], fixed[first - 1])[0]
    after = contact(disk[last], fixed[last])[0]
    check(abs(before) > 0.1, f"the surfaces slide as they meet: {before:.4f}")
    check(abs(after) < 0.01 * abs(before),
          f"friction stops the sliding within the contact: {after:.2e} (from {before:.4f})")
    # The dashpot pulls (F_n < 0) as the disks part; friction then has nothing to press on.
    bound = max(abs(ft) - mu * max(fn, 0.0)
                for _, fn, ft in (contact(disk[i], fixed[i]) for i in touching))
    check(bound <= 1e-9, f"|F_t| <= {mu} max(F_n, 0) at every step (largest excess {bound:.2e})")
    spin = disk[last]["wz"]
    check(spin * before > 0 and abs(spin) > 1,
          f"the friction spins the disk the way it slid: omega {spin:.3f}, sliding {before:.4f}")
finish()
