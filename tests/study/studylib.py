"""Shared by the ctests that drive tools/fdparticle-study (check_study.py,
check_temporal_order.py): the command line, a fresh work directory, one study run, and
check() with a failure count."""
import argparse
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
failures = 0


def check(condition, message):
    global failures
    print(("ok: " if condition else "FAIL: ") + message, flush=True)
    if not condition:
        failures += 1
    return condition


def arguments():
    """--tool, --executable, --work; the work directory is emptied."""
    p = argparse.ArgumentParser()
    p.add_argument("--tool", required=True)
    p.add_argument("--executable", required=True)
    p.add_argument("--work", required=True)
    args = p.parse_args()
    if os.path.isdir(args.work):
        shutil.rmtree(args.work)
    os.makedirs(args.work)
    return args


def run_study(args, base_prm, options, out):
    """Run the tool on tests/study/BASE_PRM with OPTIONS, writing to OUT; print its output."""
    cmd = [sys.executable, args.tool, os.path.join(HERE, base_prm),
           "--executable", args.executable] + options + ["--output", out]
    print("running: " + " ".join(repr(c) if " " in c else c for c in cmd), flush=True)
    res = subprocess.run(cmd, capture_output=True, text=True)
    print(res.stdout)
    print(res.stderr, file=sys.stderr)
    return res
