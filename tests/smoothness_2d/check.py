"""The 2D sediment smoothness figure stays below a stored bound (issue: smooth trajectories)."""
import sys
from testlib import table, check, finish

BOUND = 0.006  # measured 0.0033 to t = 5 when stored; the seed variant (uniform, Gauss 7) gives 0.019
rows = table(sys.argv[1], "smoothness.csv")
check(len(rows) == 1 and rows[0]["samples"] >= 40, "one particle, 50 steps recorded")
check(rows[0]["smoothness"] < BOUND, f"S = {rows[0]['smoothness']:.5f} < {BOUND}")
check(rows[0]["smoothness"] > 0, "S is computed (non-zero)")
finish()
