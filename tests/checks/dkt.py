"""Two disks drafting, kissing and tumbling under the collision repulsion (tests/dkt_2d.prm).

The gaps are computed here from the centres in particles.csv, not read from the code's
statistics. The repulsion's range is the finest cell edge, h = 0.25 / 2^2 = 0.0625
(Collisions/Range = auto); with K = 100 W a disk resting on another sits at 0.9 h, so
while they kiss the gap stays near that and never reaches 0."""
import math
import sys
from testlib import table, check, finish

rows = table(sys.argv[1], "particles.csv")
R, h = 0.1, 0.0625
trailer = [r for r in rows if r["id"] == 0]
leader = [r for r in rows if r["id"] == 1]
check(len(trailer) == len(leader) > 1, f"both disks in every row ({len(trailer)} steps)")
gaps = [math.hypot(a["x"] - b["x"], a["y"] - b["y"]) - 2 * R for a, b in zip(trailer, leader)]
check(min(gaps) > 0, f"the disks never overlap: smallest gap {min(gaps):.4f}")
kissing = [i for i, g in enumerate(gaps) if g < h]
check(len(kissing) > 5, f"they kiss: {len(kissing)} steps with a gap below the range h")
check(min(gaps) > 0.5 * h, f"the repulsion holds them apart: smallest gap {min(gaps):.4f} > h/2")
check(max(abs(trailer[i]["contact_fy"]) for i in kissing) > 0, "the repulsion acts while they kiss")
check(all(abs(a["contact_fx"] + b["contact_fx"]) + abs(a["contact_fy"] + b["contact_fy"]) <=
          1e-12 * (1 + abs(a["contact_fy"])) for a, b in zip(trailer, leader)),
      "the contact forces on the two disks are equal and opposite")
check(all(r["contact_fx"] == r["contact_fy"] == 0 for i, r in enumerate(trailer)
          if gaps[i] >= h and (i == 0 or gaps[i - 1] >= h)),
      "no contact force while the gap exceeds the range")
check(trailer[0]["y"] > leader[0]["y"] and trailer[-1]["y"] < leader[-1]["y"],
      f"they exchange their order in y: trailer {trailer[-1]['y']:.3f} below leader {leader[-1]['y']:.3f}")
finish()
