"""Iteration-count regression of the iterative solver: the FGMRES iterations of each step
(statistics.csv, linear_iterations) stay within a relative tolerance of the counts stored
when the preconditioner was last changed on purpose. More iterations mean a preconditioner
that got worse; far fewer, one that no longer does what was measured (doc/scaling.md).
Usage: linear_iterations.py OUTPUT_DIR TOLERANCE COUNT [COUNT ...] (one count per step)."""
import sys
from testlib import table, check, finish

out_dir, tolerance = sys.argv[1], float(sys.argv[2])
stored = [int(c) for c in sys.argv[3:]]
rows = table(out_dir, "statistics.csv")
check(len(rows) == len(stored), f"{len(rows)} steps, {len(stored)} stored counts")
for row, expected in zip(rows, stored):
    its = int(row["linear_iterations"])
    check(abs(its - expected) <= tolerance * expected,
          f"step {int(row['step'])}: {its} FGMRES iterations, stored {expected} "
          f"(within {100 * tolerance:.0f} %)")
finish()
