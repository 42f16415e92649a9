"""Seed §3.4: started from the hydrostatic pressure, the discrete system is already solved.
The seed reports a first residual of 3.52e-12 (2-norm); we require <= 1e-10."""
import sys
from testlib import table, check, finish

stats = table(sys.argv[1], "statistics.csv")
for row in stats:
    check(row["initial_residual"] <= 1e-10,
          f"step {int(row['step'])}: first residual {row['initial_residual']:.3e} <= 1e-10")
    check(row["nonlinear_iterations"] == 0, f"step {int(row['step'])}: no Newton iteration needed")
    check(row["max_velocity"] <= 1e-10, f"step {int(row['step'])}: max |u| = {row['max_velocity']:.3e}")
finish()
