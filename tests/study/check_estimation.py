#!/usr/bin/python3
"""ctest study_estimation: the grid-convergence estimate of tools/fdparticle-study on
synthetic data (no fdparticle runs).

The tool is loaded as a module; grid_convergence() and recommendation() get
  - f = 1 + 0.3 h^2 at h = 1/8, 1/16, 1/32 (constant ratio 2) and at h = 1/8, 1/12, 1/16
    (ratios 1.5 and 1.33, Celik's fixed-point iteration): order 2 to 1e-6, extrapolated
    value 1 to 1e-8, monotone (asymptotic), e_a, e_ext and GCI_fine as defined, and the
    cheapest run per error target named;
  - four runs of f = 1 + 0.3 h^2: the asymptotic-range check GCI_32/(r^p GCI_21) = f1/f2;
  - an oscillatory sequence: oscillatory, no order, no GCI, recommendation withheld;
  - a divergent one (differences growing with refinement): divergent, no GCI;
  - order 5 (outside [0.5, 3]): monotone, pre-asymptotic, no GCI;
  - two runs: no order; three equal values: unchanged.

Usage: check_estimation.py --tool tools/fdparticle-study
"""
import argparse
import os
import sys
from importlib.machinery import SourceFileLoader
from importlib.util import module_from_spec, spec_from_loader

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from testlib import check, failed  # noqa: E402


def load(path):
    loader = SourceFileLoader("fdparticle_study", path)
    module = module_from_spec(spec_from_loader("fdparticle_study", loader))
    loader.exec_module(module)
    return module


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--tool", required=True)
    tool = load(p.parse_args().tool)
    gc = tool.grid_convergence

    def f(h, p=2.0):
        return 1 + 0.3 * h ** p

    for hs in ([1 / 8, 1 / 16, 1 / 32], [1 / 8, 1 / 12, 1 / 16]):
        c = gc(hs, [f(h) for h in hs])
        name = f"f = 1 + 0.3 h^2 at h = {', '.join('1/%g' % (1 / h) for h in hs)}"
        check(c["classification"] == tool.ASYMPTOTIC and c["asymptotic"],
              f"{name}: {c['classification']}")
        check(c["order"] is not None and abs(c["order"] - 2) < 1e-6, f"{name}: order {c['order']}")
        check(c["extrapolated"] is not None and abs(c["extrapolated"] - 1) < 1e-8,
              f"{name}: extrapolated {c['extrapolated']!r}")
        f1, f2 = f(hs[-1]), f(hs[-2])
        r21 = hs[-2] / hs[-1]
        e_a = abs((f1 - f2) / f1)
        check(c["e_a"] is not None and abs(c["e_a"] - e_a) < 1e-12, f"{name}: e_a {c['e_a']!r}")
        check(c["e_ext"] is not None and abs(c["e_ext"] - (f1 - 1) / 1) < 1e-8,
              f"{name}: e_ext {c['e_ext']!r} = (f1 - 1)/1 = {f1 - 1!r}")
        gci = 1.25 * e_a / (r21 ** 2 - 1)
        check(c["gci"] is not None and abs(c["gci"] - gci) < 1e-9 * gci,
              f"{name}: GCI_fine {c['gci']!r} = 1.25 e_a/(r21^2 - 1) = {gci!r}")
        check(c["runs"] == [2, 1, 0], f"{name}: the runs used, finest first: {c['runs']}")
        # errors against f_ext = 1 are 0.3 h^2; the middle run is the cheapest one just below
        # its own error
        runs = [{"run": i, "relative_error": 0.3 * h ** 2, "wall_seconds": 1 / h} for i, h in enumerate(hs)]
        rec = tool.recommendation(c, runs, 1.01 * 0.3 * hs[1] ** 2)
        check(isinstance(rec, dict) and rec["run"] == 1, f"{name}: recommended run {rec}")
        check(tool.recommendation(c, runs, 1e-6) is None, f"{name}: no run reaches 1e-6")

    hs = [1 / 4, 1 / 8, 1 / 16, 1 / 32]
    c = gc(hs, [f(h) for h in hs])
    expected = f(1 / 32) / f(1 / 16)
    check(c["check_ratio"] is not None and abs(c["check_ratio"] - expected) < 1e-9,
          f"four runs: GCI_32/(r^p GCI_21) = {c['check_ratio']!r} (f1/f2 = {expected!r})")

    hs = [1 / 8, 1 / 16, 1 / 32]
    osc = gc(hs, [1.02, 0.99, 1.005])
    check(osc["classification"] == tool.OSCILLATORY and not osc["asymptotic"],
          f"1.02, 0.99, 1.005: {osc['classification']}")
    check(osc["order"] is None and osc["gci"] is None and osc["extrapolated"] is None,
          "oscillatory: no order, no extrapolated value, no GCI")
    check("refine further" in osc["warning"], f"oscillatory: warning '{osc['warning']}'")
    runs = [{"run": i, "relative_error": e, "wall_seconds": w}
            for i, (e, w) in enumerate([(0.02, 1), (0.01, 2), (0.005, 4)])]
    check(tool.recommendation(osc, runs, 0.1) == tool.NOT_TRUSTED,
          f"oscillatory: recommendation withheld ('{tool.recommendation(osc, runs, 0.1)}')")

    div = gc(hs, [1.0, 1.01, 1.1])          # |e21| = 0.09 > |e32| = 0.01: grows with refinement
    check(div["classification"] == tool.DIVERGENT and div["gci"] is None and div["order"] is None,
          f"1.0, 1.01, 1.1 at h = 1/8, 1/16, 1/32: {div['classification']}, R = {div['R']}")
    check(tool.recommendation(div, runs, 0.1) == tool.NOT_TRUSTED, "divergent: recommendation withheld")

    pre = gc(hs, [f(h, 5.0) for h in hs])
    check(pre["classification"] == tool.PRE_ASYMPTOTIC and pre["gci"] is None
          and pre["order"] is not None and abs(pre["order"] - 5) < 1e-6,
          f"order 5: {pre['classification']}, order {pre['order']}, no GCI")

    two = gc([1 / 8, 1 / 16], [f(1 / 8), f(1 / 16)])
    check(two["order"] is None and two["gci"] is None and two["classification"].startswith("too few runs (2)"),
          f"two runs: '{two['classification']}', order {two['order']}")
    same = gc(hs, [1.0, 1.0, 1.0])
    check(same["classification"] == tool.UNCHANGED and same["gci"] is None, f"1, 1, 1: {same['classification']}")

    print(f"{failed()} check(s) failed" if failed() else "all checks passed")
    return 1 if failed() else 0


if __name__ == "__main__":
    sys.exit(main())
