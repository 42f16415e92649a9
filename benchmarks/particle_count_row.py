#!/usr/bin/env python3
"""One CSV row of the particle-count benchmarks (benchmarks/particle_count_2d.sh and
particle_count_3d.sh) from a finished run WORK/NAME (its log, statistics.csv and the peak
memory /usr/bin/time wrote to WORK/NAME.mem):

    PREFIX,particle_unknowns,dofs,steps,newton_iterations_per_step,
    [linear_iterations_per_step,]seconds_per_step,assembly_seconds_per_step,
    solve_seconds_per_step,peak_MB

Usage: particle_count_row.py WORK NAME PREFIX [--linear]
"""
import csv
import re
import sys

work, name, prefix = sys.argv[1:4]
linear = "--linear" in sys.argv[4:]
log = open(f"{work}/{name}.log").read()


def section(title):
    """Seconds in one TimerOutput section of the log (0 if it did not run)."""
    m = re.search(r"\|\s*" + title + r"\s*\|\s*\d+\s*\|\s*([0-9.]+(?:e[+-]?\d+)?)(m?s)", log)
    return float(m.group(1)) / (1000 if m.group(2) == "ms" else 1) if m else 0.0


rows = list(csv.DictReader(open(f"{work}/{name}/statistics.csv")))
steps = len(rows)
unknowns = int(re.search(r"\+ (\d+) particle unknowns", log).group(1))
dofs = int(rows[-1]["dofs"])
total = sum(float(r["wall_seconds"]) for r in rows)
newton = sum(int(r["nonlinear_iterations"]) for r in rows) / steps
iterations = sum(int(r["linear_iterations"]) for r in rows) / steps
assembly = section("assemble system") + section("assemble residual")
peak = int(open(f"{work}/{name}.mem").read().split()[-1]) / 1024
fields = [prefix, unknowns, dofs, steps, f"{newton:.2f}"]
if linear:
    fields.append(f"{iterations:.1f}")
fields += [f"{total / steps:.3f}", f"{assembly / steps:.3f}", f"{section('solve') / steps:.3f}",
           f"{peak:.0f}"]
print(",".join(str(f) for f in fields))
