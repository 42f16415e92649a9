#!/usr/bin/python3
"""The lubrication correction between two equal spheres approaching each other (doc/
particles.md, 'Lubrication'). Two spheres (a = 1, mu = 1) at the centre of the box of
prm/validation/wall.prm move toward each other along y at U = 1 each, steady Stokes in
one step (as benchmarks/lubrication_wall.py runs the wall), with Lubrication/Enabled =
true, at gaps g/a = 0.03 ... 1 between their surfaces (2D: from 0.05) and particle refinement levels 3
(d/h = 4; --levels 3 4 adds d/h = 8, about 300 k DoFs and 6 GB per run).

By symmetry the mid-plane carries no normal velocity and no shear stress, so each sphere
moves as one approaching a free surface at the half-gap g/2, for which Brenner (J. Fluid
Mech. 1961) gives the exact drag factor lambda = F/(6 pi mu a U); it is summed here. The
box's walls, 7a from the spheres, add to it: the single sphere of the same box at gap 1a
from the floor is 1.3 times Brenner's unbounded value in the wall benchmark, but the two
spheres' opposite Stokeslets cancel in the far field, so the pair feels the box much less
(compare the largest gap). The run reports the resolved force (particles.csv fy) and the
correction (contact_fy), so it gives lambda with and without the correction, and the
shift s: the gap widening g + s at which the free-surface lambda equals the resolved one,
to be compared with the 'auto' Gap shift of a pair. Writes doc/lubrication_pair.csv and
doc/lubrication_pair.png.

--dimension 2 runs the same scene with two cylinders (per unit length; lambda = F/(mu U)).
No exact solution exists in 2D, so the reference is the resolved force of the same scene
at d/h = 512 and 1024 extrapolated to h -> 0 (--reference-dh, as benchmarks/
lubrication_wall.py), and the shift s solves resolved = reference -
2 (C(g) - C(g + s)) for the leading term C(g) = 3 sqrt(2) pi (a*/g)^(3/2), a* = a/2, at
the relative velocity 2U. Writes doc/lubrication_pair_2d.csv and .png.

Regenerate (from the top of the repository, after scripts/build.sh; about 4 min for
--levels 3, 15 min with 4; 2D: 15 min):
    /usr/bin/python3 benchmarks/lubrication_pair.py [--executable PATH] [--work DIR]
        [--levels 3] [--dimension 2 --levels 3 4 5 [--reference-dh 512 1024]]
"""
import math
import os
from importlib.machinery import SourceFileLoader

TOP = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
WALL = SourceFileLoader("lubrication_wall", os.path.join(TOP, "benchmarks", "lubrication_wall.py")).load_module()
DOC = os.path.join(TOP, "doc")
# 2D starts at 0.05a: below it even d/h = 1024 (2.6 cells at 0.02a) has not converged.
GAPS = {3: (0.03, 0.05, 0.1, 0.15, 0.25, 0.4, 0.6, 1.0), 2: (0.05, 0.1, 0.15, 0.25, 0.4, 0.6, 1.0)}
CENTRE = 8.0  # the mid-plane of the 16a box


def free_surface(delta):
    """lambda of a sphere moving normal to a plane free surface at gap delta/a
    (Brenner 1961)."""
    alpha = math.acosh(1 + delta)
    total = 0.0
    for n in range(1, 100000):
        if (2 * n + 1) * alpha > 600:  # the terms have converged long before cosh overflows
            break
        num = 4 * math.cosh((n + 0.5) * alpha) ** 2 + (2 * n + 1) ** 2 * math.sinh(alpha) ** 2
        den = 2 * math.sinh((2 * n + 1) * alpha) - (2 * n + 1) * math.sinh(2 * alpha)
        total += n * (n + 1) / ((2 * n - 1) * (2 * n + 3)) * (num / den - 1)
    return 4.0 / 3.0 * math.sinh(alpha) * total


def cylinder_shift(gap, resolved, reference):
    """s with resolved = reference - 2 (C(gap) - C(gap + s)), C the 2D leading term for
    a* = a/2."""
    C = lambda g: 2 * 3 * math.sqrt(2) * math.pi * (0.5 / g) ** 1.5
    wide = C(gap) - reference + resolved
    return 0.5 * (2 * 3 * math.sqrt(2) * math.pi / wide) ** (2 / 3) - gap if wide > 0 else float("nan")


def run(args, base, levels, gap, subdivisions=4):
    """Resolved force and correction, in units of lambda, of the upper ball at the gap
    (2D: on subdivisions^2 base cells)."""
    offset = 1 + gap / 2
    return WALL.run_scene(args, base, f"pair_{args.dimension}d_{subdivisions}_lv{levels}_gap{gap}",
                          levels, [(CENTRE - offset, 1), (CENTRE + offset, -1)], subdivisions)


def main():
    args, base = WALL.arguments(__doc__, "lubrication_pair", [3])
    if args.dimension == 2:
        references = WALL.extrapolated_reference(
            lambda subdivisions, levels, gap: run(args, base, levels, gap, subdivisions)[0],
            GAPS[2], args.reference_dh)
    rows = []
    for levels in args.levels:
        h = WALL.cell_size(levels)
        for gap in GAPS[args.dimension]:
            resolved, correction = run(args, base, levels, gap)
            if args.dimension == 3:
                ref = free_surface(gap / 2)
                shift = WALL.effective_gap(resolved, lambda g: free_surface(g / 2)) - gap
            else:
                ref = references[gap]
                shift = cylinder_shift(gap, resolved, ref)
            rows.append(WALL.table_row(h, gap, ref, resolved, shift, correction))
    reference_dh = "{} and {}, extrapolated".format(*args.reference_dh)
    reference = "Brenner lambda" if args.dimension == 3 else f"reference (d/h = {reference_dh})"
    header = ["d/h", "gap/a", "gap/h", reference, "resolved", "error %", "shift s/a",
              "correction", "error with correction %"]
    stem = os.path.join(DOC, "lubrication_pair" + ("" if args.dimension == 3 else "_2d"))
    title = ("Two spheres approaching each other: error of lambda against Brenner (1961)"
             if args.dimension == 3 else f"Two cylinders approaching each other: error against d/h = {reference_dh}")
    WALL.write_results(stem, header, rows, args.levels,
                       os.path.join(args.work, f"lubrication_pair_{args.dimension}d.dat"), title,
                       "gap g/a between the balls")


if __name__ == "__main__":
    main()
