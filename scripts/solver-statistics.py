#!/usr/bin/python3
"""Print named numbers of the first "iterative solver:" line of a run's output.

    scripts/solver-statistics.py LOG NAME...

`Solver/Iterative solver statistics = true` makes the program print that line for every
linear solve (IterativeSolver::solve); the first one is the solve that built the
preconditioner. The numbers are printed comma-separated in the order asked for, so the
benchmark scripts do not each parse the line their own way. Names: see FIELDS.
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

def main(argv):
    if len(argv) < 3:
        sys.exit(__doc__ + "\n" + "".join(f"    {name}\n" for name in FIELDS))
    with open(argv[1], encoding="utf-8", errors="replace") as f:
        line = next((l for l in f if "iterative solver:" in l), None)
    if line is None:
        sys.exit(f"{argv[1]}: no 'iterative solver:' line (Iterative solver statistics off?)")
    values = []
    for name in argv[2:]:
        if name not in FIELDS:
            sys.exit(f"unknown name {name}; known: {', '.join(FIELDS)}")
        m = re.search(FIELDS[name], line)
        if m is None:
            sys.exit(f"{argv[1]}: the statistics line has no {name}")
        values.append(m.group(1))
    print(",".join(values))


if __name__ == "__main__":
    main(sys.argv)
