#!/usr/bin/python3
"""ctest temporal_order_2d: the observed temporal order of BDF1 and BDF2 (doc/studies.md §2).

Runs tools/fdparticle-study on tests/study/temporal_2d.prm (a heavy disk still accelerating
at t = 0.2, Stokes, fixed 16 x 32 mesh, level set, fixed pairing time step) for BDF1 and
BDF2 with dt = 0.02, 0.01, 0.005 (about 15 s) and reads the disk's height y(0.2) and
velocity v_y(0.2) of each run from study.csv. The observed order from successive
differences, p = log2(|q(dt) - q(dt/2)| / |q(dt/2) - q(dt/4)|), must be that of the scheme:
BDF1 in [0.7, 1.3], BDF2 in [1.6, 2.6] (measured: 0.96 and 2.07 for both quantities; the
time errors are about 1e-5 in y, far above the solver's round-off). The two schemes'
Richardson extrapolations, q(dt/4) + (q(dt/4) - q(dt/2)) / (2^p - 1) with p = 1 and 2, must
agree to a tenth of BDF1's change over the last halving (measured: 2 %): both converge to
the same limit. With the seed's pairing (alpha from the current dt) BDF2 measures 1.52 in
y(0.2) and -0.79 in v_y(0.2), so this test fails if the pairing follows dt again.

Usage: check_temporal_order.py --tool tools/fdparticle-study --executable build/fdparticle --work DIR
"""
import csv
import math
import os
import sys

import studylib
from studylib import check

STEPS = ["0.02", "0.01", "0.005"]
# scheme: (order of the scheme, accepted band of the observed order)
SCHEMES = {"BDF1": (1, (0.7, 1.3)), "BDF2": (2, (1.6, 2.6))}
QOIS = ["y-at:0.2", "vy-at:0.2"]


def main():
    args = studylib.arguments()
    out = os.path.join(args.work, "study")
    res = studylib.run_study(args, "temporal_2d.prm",
                             ["--vary", "Time/Scheme=" + ",".join(SCHEMES),
                              "--vary", "Time/Time step=" + ",".join(STEPS),
                              "--qoi", ",".join(QOIS), "--reference", "group-finest",
                              "--work", os.path.join(args.work, "runs")], out)
    if not check(res.returncode == 0, "the study ran"):
        sys.exit(1)
    rows = list(csv.DictReader(open(os.path.join(out, "study.csv"))))
    # The primary QoI is in the column 'qoi', the others in columns named after them.
    columns = {QOIS[0]: "qoi", **{q: q for q in QOIS[1:]}}
    for qoi in QOIS:
        values = {(r["Time/Scheme"], r["Time/Time step"]): float(r[columns[qoi]]) for r in rows}
        if not check(len(values) == len(SCHEMES) * len(STEPS)
                     and all(math.isfinite(v) for v in values.values()),
                     f"{qoi}: {len(SCHEMES) * len(STEPS)} finite values"):
            continue
        extrapolated, last_change = {}, {}
        for scheme, (p, (low, high)) in SCHEMES.items():
            q = [values[(scheme, s)] for s in STEPS]
            d1, d2 = q[0] - q[1], q[1] - q[2]
            order = math.log2(abs(d1 / d2)) if d1 != 0 and d2 != 0 else float("nan")
            check(low <= order <= high,
                  f"{scheme} {qoi}: {', '.join('%.10g' % v for v in q)}; observed order "
                  f"{order:.2f} (expected in [{low}, {high}])")
            extrapolated[scheme] = q[2] - d2 / (2 ** p - 1)
            last_change[scheme] = abs(d2)
        gap = abs(extrapolated["BDF1"] - extrapolated["BDF2"])
        check(gap <= 0.1 * last_change["BDF1"],
              f"{qoi}: extrapolated BDF1 {extrapolated['BDF1']:.10g}, BDF2 "
              f"{extrapolated['BDF2']:.10g} differ by {gap:.2g} (at most a tenth of BDF1's "
              f"last change {last_change['BDF1']:.2g})")
    print("PASSED" if studylib.failures == 0 else f"FAILED ({studylib.failures})")
    sys.exit(1 if studylib.failures else 0)


if __name__ == "__main__":
    main()
