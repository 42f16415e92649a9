#!/usr/bin/python3
"""Print named numbers of the first "iterative solver:" line of a run's output.

    scripts/solver-statistics.py [--run] LOG NAME...

`Solver/Iterative solver statistics = true` makes the program print that line for every
linear solve (IterativeSolver::solve); the first one is the solve that built the
preconditioner. The numbers are printed comma-separated in the order asked for, so the
benchmark scripts do not each parse the line their own way. Names: see FIELDS.

--run: the totals over every solve of the run instead (a run with many steps rebuilds its
preconditioner many times): sums of the per-solve numbers; of the set-up times, the sum over
the builds; of patch_apply_seconds, which each line counts from the last build, the sum of
each build's last value. Only the times and iteration counts can be totalled.
"""

import re
import sys

NUMBER = r"([0-9.eE+-]+)"

# name: the pattern whose first group is the number.
FIELDS = {
    "outer_iterations": NUMBER + r" outer iterations",
    "inner_iterations": r"outer iterations \(" + NUMBER + r" inner\)",
    "relative_residual": r"relative residual " + NUMBER,
    "matrix_nonzeros": r"Newton matrix " + NUMBER + r" non-zeros",
    "velocity_nonzeros": NUMBER + r" of them in the velocity block",
    "free_unknowns": r"Krylov vectors of the " + NUMBER + r" free",
    "patch_unknowns": r"cut-cell patch " + NUMBER + r" unknowns",
    "patch_mb": r"factored in " + NUMBER + r" MB",
    "slow_pressure_modes": r"\((?:at least )?" + NUMBER + r" slow pressure modes\)",
    "setup_seconds": r"built in " + NUMBER + r" s",
    "patch_setup_seconds": r"built in [0-9.eE+-]+ s \(patch " + NUMBER + r" s\)",
    "iterate_seconds": r"iterations " + NUMBER + r" s \(",
    "patch_apply_seconds": r"its patch " + NUMBER + r" s",
    "product_seconds": r"operator products " + NUMBER + r" s",
    "velocity_cycle_seconds": r"velocity V-cycles " + NUMBER + r" s",
    "multiplier_cycle_seconds": r"multiplier V-cycles " + NUMBER + r" s",
    "particle_block_seconds": r"particle block " + NUMBER + r" s",
}

# The numbers that --run can total; the rest describe one solve.
TOTALS = {"outer_iterations", "inner_iterations", "setup_seconds", "patch_setup_seconds",
          "iterate_seconds", "patch_apply_seconds", "product_seconds",
          "velocity_cycle_seconds", "multiplier_cycle_seconds", "particle_block_seconds"}


def number(line, name, log):
    m = re.search(FIELDS[name], line)
    if m is None:
        sys.exit(f"{log}: the statistics line has no {name}")
    return m.group(1)


def run_total(lines, name, log):
    if name in ("setup_seconds", "patch_setup_seconds"):
        return sum(float(number(l, name, log)) for l in lines if "built in" in l)
    if name == "patch_apply_seconds":
        total, last = 0.0, 0.0
        for l in lines:
            if "built in" in l:
                total += last
            last = float(number(l, name, log))
        return total + last
    return sum(float(number(l, name, log)) for l in lines)


def main(argv):
    run = len(argv) > 1 and argv[1] == "--run"
    if run:
        argv = argv[:1] + argv[2:]
    if len(argv) < 3:
        sys.exit(__doc__ + "\n" + "".join(f"    {name}\n" for name in FIELDS))
    with open(argv[1], encoding="utf-8", errors="replace") as f:
        lines = [l for l in f if "iterative solver:" in l]
    if not lines:
        sys.exit(f"{argv[1]}: no 'iterative solver:' line (Iterative solver statistics off?)")
    values = []
    for name in argv[2:]:
        if name not in FIELDS:
            sys.exit(f"unknown name {name}; known: {', '.join(FIELDS)}")
        if not run:
            values.append(number(lines[0], name, argv[1]))
        elif name in TOTALS:
            values.append(f"{run_total(lines, name, argv[1]):.6g}")
        else:
            sys.exit(f"{name} describes one solve and has no total over a run")
    print(",".join(values))


if __name__ == "__main__":
    main(sys.argv)
