"""A reused preconditioner whose cheap form misses the tolerance is rebuilt for the current
operator and the cheap form tried again (doc/method.md §8, "Preconditioner reuse"):
statistics.csv shows no inner solve (an application of the cheap form counts one inner
iteration; an inner solve counts tens) and a set-up in steps after the first on the same
mesh."""
import sys
from testlib import table, check, finish

rows = table(sys.argv[1], "statistics.csv")
check(len(rows) > 2, f"{len(rows)} steps")
inner = [int(r["step"]) for r in rows
         if int(r["inner_iterations"]) > int(r["linear_iterations"]) + 2 * int(r["nonlinear_iterations"])]
check(not inner, "no inner solve" + (f"; it ran in steps {inner}" if inner else ""))
rebuilt = [int(r["step"]) for r, before in zip(rows[1:], rows)
           if int(r["solver_setups"]) > 0 and r["dofs"] == before["dofs"]]
check(len(rebuilt) > 0, f"rebuilt on an unchanged mesh in steps {rebuilt}")
finish()
