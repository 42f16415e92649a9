"""Two disks whose cut cells touch keep their own rigid motions (tests/close_pair_2d.prm).

Disks 0-1: one moves toward a fixed one across a shared cut-cell face; 2-3: the same pair,
both moving; 4-5: the pair of 2-3 with a row of fluid cells between their cut cells. In
Stokes flow a disk approaching another squeezes the fluid out of the gap, which pushes the
other disk away and brakes the moving one; at equal gaps the force does not depend on
where the gap sits in the mesh, up to the discretisation error of a gap of about a cell."""
import sys
from testlib import table, check, finish

out = sys.argv[1]
fy = {int(r["id"]): r["fy"] for r in table(out, "particles.csv") if r["time"] > 0}
check(len(fy) == 6, "six disks after one step")
print(f"fy: {', '.join(f'{k}: {v:.3f}' for k, v in sorted(fy.items()))}")
check(fy[0] < 0 < fy[1], "the fixed disk is pushed away from the disk approaching it, which is braked")
touching, apart = 0.5 * (fy[3] - fy[2]), 0.5 * (fy[5] - fy[4])
check(apart > 10, f"the pair with fluid cells between feels the squeeze ({apart:.2f})")
check(abs(touching - apart) < 0.15 * apart,
      f"the pair whose cut cells touch feels the same squeeze force: {touching:.2f} against {apart:.2f}")
finish()
