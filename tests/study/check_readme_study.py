#!/usr/bin/python3
"""ctest study_readme_2d: the README's convergence study, small, reports what its data give.

Runs tools/fdparticle-study on prm/sediment2d.prm as README.md item 4 does (Global
refinements 0, 1, 2 x Gauss / level-set cut cells: two curves of three runs), to t = 0.25
instead of 2, and checks that the report is consistent with the
classification of each curve, whatever it is:
  - a curve not classified 'monotone (asymptotic)' has no observed order, extrapolated value
    or GCI in fits.csv, a warning saying 'refine further' on the screen and in study.md,
    errors stated as differences to a named run, and no recommended run (every target:
    'not in the asymptotic range: refine further');
  - an asymptotic curve has all of them, errors against its extrapolated value and a
    recommended run for at least one target.
The study of the two coarser levels with --jobs 2 must give the same runs (DoFs, steps,
QoIs) as these runs of the full study.

Usage: check_readme_study.py --tool tools/fdparticle-study --executable build/fdparticle --work DIR
"""
import csv
import math
import os
import sys
import time

import studylib
from studylib import check

BASE = os.path.join(studylib.HERE, "..", "..", "prm", "sediment2d.prm")
OPTIONS = ["--set", "Time/End time=0.25", "--vary", "Geometry/Global refinements=0,1,2",
           "--vary", "Quadrature/Cut cells=gauss,level set", "--qoi", "terminal-vy"]
ASYMPTOTIC = "monotone (asymptotic)"
WITHHELD = "not in the asymptotic range: refine further"


def number(text):
    try:
        return float(text)
    except ValueError:
        return None


def recommendation_columns(md):
    """{curve: [cells of the recommendation table]} from study.md."""
    lines = md.splitlines()
    start = next(i for i, l in enumerate(lines) if l.startswith("| target |"))
    header = [c.strip() for c in lines[start].strip("|").split("|")]
    columns = {h: [] for h in header[1:]}
    for line in lines[start + 2:]:
        if not line.startswith("|"):
            break
        cells = [c.strip() for c in line.strip("|").split("|")]
        for h, c in zip(header[1:], cells[1:]):
            columns[h].append(c)
    return columns


def main():
    args = studylib.arguments()
    out = os.path.join(args.work, "study")
    begin = time.monotonic()
    res = studylib.run_study(args, BASE, OPTIONS + ["--work", os.path.join(args.work, "runs")], out)
    print(f"the study took {time.monotonic() - begin:.1f} s")
    if not check(res.returncode == 0, f"the study exits with status 0 (got {res.returncode})"):
        return 1
    fits = list(csv.DictReader(open(os.path.join(out, "fits.csv"))))
    md = open(os.path.join(out, "study.md")).read()
    rows = list(csv.DictReader(open(os.path.join(out, "study.csv"))))
    recs = recommendation_columns(md)
    check(len(fits) == 2 and all(f["runs"] == "3" for f in fits), "two curves of three runs each")
    for f in fits:
        g, cls = f["group"], f["classification"]
        print(f"{g}: {cls}")
        estimates = [number(f[c]) for c in ("observed_order", "extrapolated", "gci_fine")]
        mine = [r for r in rows if r["group"] == g]
        if cls == ASYMPTOTIC:
            check(all(x is not None and math.isfinite(x) for x in estimates) and estimates[2] > 0,
                  f"{g} (asymptotic): order, extrapolated value and GCI in fits.csv: {estimates}")
            check(all(r["reference_source"] == "extrapolated" for r in mine),
                  f"{g}: errors against the extrapolated value")
            check(any(c.startswith("run ") for c in recs.get(g, [])),
                  f"{g}: a recommended run for some target: {recs.get(g)}")
            check(f"Warning: {g} is" not in md, f"{g}: no warning in study.md")
        else:
            check(all(x is None for x in estimates[1:]),
                  f"{g} ({cls}): no extrapolated value and no GCI in fits.csv")
            if cls != "monotone, pre-asymptotic":
                check(estimates[0] is None, f"{g} ({cls}): no observed order")
            check(f"warning: {g} is {cls}" in res.stdout and "refine further" in res.stdout,
                  f"{g}: warning on the screen")
            check(f"**Warning: {g} is {cls}**" in md, f"{g}: warning in study.md")
            check(all(r["reference_source"].startswith("run ") for r in mine)
                  and f"- {g}: run " in md and "not error estimates" in md,
                  f"{g}: errors stated as differences to a named run, not error estimates")
            check(recs.get(g) and all(c == WITHHELD for c in recs[g]),
                  f"{g}: no recommended run: {recs.get(g)}")
    for png in ("error_vs_dofs.png", "error_vs_wall.png", "qoi_convergence.png"):
        path = os.path.join(out, png)
        check(os.path.isfile(path) and os.path.getsize(path) > 2000, f"{png} written")

    # --jobs 2 on the two coarser levels: the same runs as the full study's first four.
    out2 = os.path.join(args.work, "study-jobs2")
    coarse = [o.replace("=0,1,2", "=0,1") for o in OPTIONS]
    begin = time.monotonic()
    res2 = studylib.run_study(args, BASE, coarse + ["--jobs", "2", "--work", os.path.join(args.work, "runs2")], out2)
    print(f"the study with --jobs 2 took {time.monotonic() - begin:.1f} s")
    if check(res2.returncode == 0, "the study with --jobs 2 exits with status 0"):
        rows2 = list(csv.DictReader(open(os.path.join(out2, "study.csv"))))
        keys = ("run", "group", "dofs", "steps", "qoi")
        check(len(rows2) == 4 and [[r[k] for k in keys] for r in rows[:4]]
              == [[r[k] for k in keys] for r in rows2],
              "--jobs 2: the same runs, DoFs, steps and QoIs")

    print(f"{studylib.failures} check(s) failed" if studylib.failures else "all checks passed")
    return 1 if studylib.failures else 0


if __name__ == "__main__":
    sys.exit(main())
