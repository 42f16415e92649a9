"""Iteration-count regression of the iterative solver: the FGMRES iterations of each step
and the iterations of the inner solves in its preconditioner (statistics.csv,
linear_iterations and inner_iterations) stay within a relative tolerance of the counts
stored when the preconditioner was last changed on purpose. More iterations mean a
preconditioner that got worse; far fewer, one that no longer does what was measured
(doc/scaling.md). The outer count follows the pressure Schur approximation and the inner
tolerance, the inner count the velocity and multiplier blocks.
Usage: linear_iterations.py OUTPUT_DIR TOLERANCE OUTER/INNER [OUTER/INNER ...] (one pair
per step)."""
import sys
from testlib import table, check, finish

out_dir, tolerance = sys.argv[1], float(sys.argv[2])
stored = [tuple(int(c) for c in pair.split("/")) for pair in sys.argv[3:]]
rows = table(out_dir, "statistics.csv")
check(len(rows) == len(stored), f"{len(rows)} steps, {len(stored)} stored counts")
for row, (outer, inner) in zip(rows, stored):
    for name, expected in (("linear_iterations", outer), ("inner_iterations", inner)):
        its = int(row[name])
        check(abs(its - expected) <= tolerance * expected,
              f"step {int(row['step'])}: {name} {its}, stored {expected} "
              f"(within {100 * tolerance:.0f} %)")
finish()
