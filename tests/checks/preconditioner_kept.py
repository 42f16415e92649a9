"""The iterative solver keeps its preconditioner across steps in which the mesh does not
change (statistics.csv: solver_setups 0 in some step after the first, with the same DoFs):
a mesh that was flagged but left unchanged by the triangulation's smoothing must not
rebuild the DoFs and everything the solvers built on them (doc/method.md §8,
"Preconditioner reuse")."""
import sys
from testlib import table, check, finish

rows = table(sys.argv[1], "statistics.csv")
check(len(rows) > 2, f"{len(rows)} steps")
kept = [int(r["step"]) for r, before in zip(rows[1:], rows) if int(r["solver_setups"]) == 0 and r["dofs"] == before["dofs"]]
check(len(kept) > 0, f"the preconditioner kept in steps {kept} of {len(rows)}")
finish()
