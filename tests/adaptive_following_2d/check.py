"""The finest cells stay on the moving surface, and the mesh follows instead of growing."""
import sys
from testlib import table, check, finish

out = sys.argv[1]
stats = table(out, "statistics.csv")
parts = table(out, "particles.csv")
check(all(r["coarse_cut_cells"] == 0 for r in stats),
      "after every step all cells cut by the surface are at the finest level")
drop = parts[0]["y"] - parts[-1]["y"]
check(drop > 0.125, f"the disk fell {drop:.3f} > one base cell (0.125)")
cells = [r["cells"] for r in stats]
check(max(cells) <= 1.15 * cells[0], f"the mesh does not grow: {cells[0]:.0f} -> max {max(cells):.0f} cells")
check(min(cells) > 128, "the mesh stays refined around the disk (more than the 128 base cells)")
finish()
