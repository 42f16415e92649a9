#!/usr/bin/python3
"""ctest temporal_order_2d: the observed temporal order of BDF1 and BDF2 (doc/studies.md).

Runs tools/fdparticle-study on tests/study/temporal_2d.prm (settling disk, Stokes, fixed
16 x 32 mesh, level set, fixed pairing time step) for BDF1 and BDF2 with dt = 0.02, 0.01,
0.005 (about 20 s) and reads the disk's height y(0.2) of each run from study.csv. The
observed order from successive differences, p = log2(|y(dt) - y(dt/2)| / |y(dt/2) - y(dt/4)|),
must be that of the scheme: BDF1 in [0.7, 1.3], BDF2 above 1.6 (the analytic orders of the
schemes, 1 and 2). Both schemes must agree at the finest dt to 1e-6 (the displacement is
2.3e-3). With the seed's pairing (alpha from the current dt) BDF2 measures 0.5-0.7 here,
so this test fails if the pairing follows dt again (doc/studies.md §2).

Usage: check_temporal_order.py --tool tools/fdparticle-study --executable build/fdparticle --work DIR
"""
import csv
import math
import os
import sys

import studylib
from studylib import check


def main():
    args = studylib.arguments()
    out = os.path.join(args.work, "study")
    steps = ["0.02", "0.01", "0.005"]
    res = studylib.run_study(args, "temporal_2d.prm",
                             ["--vary", "Time/Scheme=BDF1,BDF2",
                              "--vary", "Time/Time step=" + ",".join(steps),
                              "--qoi", "y-at:0.2", "--reference", "group-finest",
                              "--work", os.path.join(args.work, "runs")], out)
    if not check(res.returncode == 0, "the study ran"):
        sys.exit(1)
    rows = list(csv.DictReader(open(os.path.join(out, "study.csv"))))
    y = {(r["Time/Scheme"], r["Time/Time step"]): float(r["qoi"]) for r in rows}
    check(len(y) == 6 and all(math.isfinite(v) for v in y.values()), "six finite heights y(0.2)")
    finest = {}
    for scheme, bounds in (("BDF1", (0.7, 1.3)), ("BDF2", (1.6, math.inf))):
        d1 = abs(y[(scheme, steps[0])] - y[(scheme, steps[1])])
        d2 = abs(y[(scheme, steps[1])] - y[(scheme, steps[2])])
        order = math.log2(d1 / d2) if d1 > 0 and d2 > 0 else float("nan")
        check(bounds[0] <= order <= bounds[1],
              f"{scheme}: y(0.2) = {', '.join('%.10f' % y[(scheme, s)] for s in steps)}; "
              f"observed order {order:.2f} (expected in [{bounds[0]}, {bounds[1]}])")
        finest[scheme] = y[(scheme, steps[-1])]
    check(abs(finest["BDF1"] - finest["BDF2"]) < 1e-6,
          f"BDF1 and BDF2 agree at dt = {steps[-1]}: {finest['BDF1']:.10f} vs {finest['BDF2']:.10f}")
    print("PASSED" if studylib.failures == 0 else f"FAILED ({studylib.failures})")
    sys.exit(1 if studylib.failures else 0)


if __name__ == "__main__":
    main()
