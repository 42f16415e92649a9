"""A dense disk bouncing off a fixed disk with the spring-dashpot contact (tests/bounce_2d.prm).

The rebound speed over the impact speed can be neither above the restitution coefficient
(the fluid and the time integration only take energy) nor far below it: the fluid is
light and nearly inviscid, and the contact lasts about 6.5 time steps, for which the
integration alone returns about 0.82 of a dry bounce (tests/unit/collisions.cc). A contact
that began only when the surfaces touch would meet the discrete flow in the cells the
disks share and stop the disk with almost no rebound (doc/particles.md). The gaps are
computed here from the centres; h = 1/4 / 2^3 is the finest cell edge, the range of the
contact (Collisions/Range = auto)."""
import math
import sys
from testlib import table, parameters, check, finish

out = sys.argv[1]
prm = parameters(out)
rows = table(out, "particles.csv")
e = float(prm["Collisions/Restitution coefficient"])
R, h = 0.1, 1.0 / 4 / 2 ** 3
disk = [r for r in rows if r["id"] == 0]
fixed = [r for r in rows if r["id"] == 1]
gaps = [math.hypot(a["x"] - b["x"], a["y"] - b["y"]) - 2 * R for a, b in zip(disk, fixed)]
touching = [i for i, r in enumerate(disk) if r["contact_fy"] != 0]
check(len(touching) > 2, f"a contact of {len(touching)} steps")
if touching:
    first, last = touching[0], touching[-1]
    impact = -min(r["vy"] for r in disk[:first])
    rebound = max((r["vy"] for r in disk[last + 1:]), default=0.0)
    ratio = rebound / impact
    check(0.6 * e < ratio <= e,
          f"rebound {rebound:.4f} / impact {impact:.4f} = {ratio:.3f}, between 0.6 e and e = {e}")
    check(all(gaps[i] < h for i in touching), "a contact force only within the range h")
    check(all(fixed[i]["contact_fy"] == -disk[i]["contact_fy"] for i in touching),
          "equal and opposite on the two disks")
check(min(gaps) > 0, f"the disks never touch: smallest gap {min(gaps):.4f}")
finish()
