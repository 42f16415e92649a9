#!/usr/bin/env python3
"""Run one fdparticle regression/validation test, ASPECT style.

A test is tests/NAME.prm; directives in its comment lines say what to check:

  # test-ranks: 1, 2               run on each number of MPI ranks (default 1); with several,
                                   particles.csv must agree between them (relative tolerance
  # test-rank-tolerance: 1e-8      given here, default 1e-8)
  # test-expect-error: TEXT        the run must fail (non-zero exit), print TEXT on stderr
                                   and leave no output directory behind
  # test-expect-runtime-error: TEXT  the same, but the run may have written output first
  # test-args: ARGS                run 'fdparticle ARGS' instead of 'fdparticle NAME.prm'
                                   (@TESTS@ in ARGS and in the prm: the tests/ directory)
  # test-compare: FILE [FILE ...]  compare output files with tests/NAME/FILE (CSV, numeric,
  # test-tolerance: REL ABS        |a-b| <= ABS + REL*|b|; wall_seconds is never compared)
  # test-check: SCRIPT [ARGS]      run tests/SCRIPT OUTPUT_DIR [ARGS]; it exits non-zero on failure
  # test-restart-at: T             also run to End time T with checkpoints, then resume
                                   (Checkpointing/Resume = true) to the End time of the
                                   prm, after mimicking a kill during the last checkpoint
                                   write (only checkpoint.old and a partial checkpoint.new
                                   left); particles.csv and the step rows of
                                   statistics.csv must equal those of the uninterrupted
  # test-restart-tolerance: REL ABS  run (default 1e-12 1e-14)

The output directory set in the prm is replaced by --work/ranks-N.
"""
import argparse
import csv
import os
import re
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
IGNORED_COLUMNS = {"wall_seconds"}


def directives(prm_text):
    found = {}
    for line in prm_text.splitlines():
        m = re.match(r"^#\s*(test-[a-z-]+):\s*(.*)$", line)
        if m:
            found[m.group(1)] = m.group(2).strip()
    return found


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], rows[1:]


def compare_csv(actual, expected, rel, abs_tol):
    """Return a list of mismatch descriptions (empty: files agree)."""
    ha, ra = read_csv(actual)
    he, re_ = read_csv(expected)
    problems = []
    # Columns added to a table later do not break stored output; missing ones do.
    missing = [h for h in he if h not in ha]
    if missing:
        return [f"{os.path.basename(actual)}: columns {missing} missing (header {ha})"]
    ra = [[row[ha.index(h)] for h in he] for row in ra]
    ha = he
    if len(ra) != len(re_):
        return [f"{os.path.basename(actual)}: {len(ra)} rows, expected {len(re_)}"]
    for i, (a_row, e_row) in enumerate(zip(ra, re_)):
        for name, a, e in zip(ha, a_row, e_row):
            if name in IGNORED_COLUMNS:
                continue
            a, e = float(a), float(e)
            if not abs(a - e) <= abs_tol + rel * abs(e):
                problems.append(f"{os.path.basename(actual)} row {i + 1} column {name}: "
                                f"{a!r} vs expected {e!r}")
    return problems


def run(executable, args, ranks, cwd):
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    cmd = [executable] + args
    if ranks > 1:
        cmd = ["mpirun", "--oversubscribe", "-np", str(ranks)] + cmd
    print("running:", " ".join(cmd), flush=True)
    return subprocess.run(cmd, cwd=cwd, env=env, capture_output=True, text=True)


def check_restart(opts, text, d, ranks, full_dir):
    """Interrupted run + resume must reproduce the uninterrupted run in full_dir."""
    part_dir = full_dir + "-restarted"
    checkpoint = os.path.join(part_dir, "checkpoint")
    problems = []
    for stage, extra in (("first half", f"subsection Time\n  set End time = {d['test-restart-at']}\nend\n"),
                         ("resumed", "subsection Checkpointing\n  set Resume = true\nend\n")):
        prm = os.path.join(opts.work, f"restart-{ranks}-{stage.replace(' ', '-')}.prm")
        with open(prm, "w") as f:
            f.write(text + f"\nsubsection Output\n  set Directory = {part_dir}\nend\n" + extra)
        if stage == "resumed":
            # A kill between the renames of a checkpoint write leaves DIR.old and DIR.new.
            os.rename(checkpoint, checkpoint + ".old")
            os.makedirs(checkpoint + ".new")
            with open(os.path.join(checkpoint + ".new", "state.txt.tmp"), "w") as f:
                f.write("partial")
        result = run(opts.executable, [prm], ranks, opts.work)
        sys.stdout.write(result.stdout[-2000:])
        sys.stderr.write(result.stderr[-2000:])
        if result.returncode != 0:
            return [f"restart test, {stage} run exited with {result.returncode}"]
    rel, abs_tol = (float(x) for x in d.get("test-restart-tolerance", "1e-12 1e-14").split())
    for p in compare_csv(os.path.join(part_dir, "particles.csv"),
                         os.path.join(full_dir, "particles.csv"), rel, abs_tol):
        problems.append(f"restarted vs uninterrupted: {p}")
    steps = [read_csv(os.path.join(x, "statistics.csv"))[1] for x in (part_dir, full_dir)]
    if [r[0] for r in steps[0]] != [r[0] for r in steps[1]]:
        problems.append("restarted statistics.csv has other steps than the uninterrupted one")
    return problems


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--executable", required=True)
    parser.add_argument("--prm", required=True)
    parser.add_argument("--work", required=True)
    opts = parser.parse_args()

    name = os.path.splitext(os.path.basename(opts.prm))[0]
    with open(opts.prm) as f:
        text = f.read().replace("@TESTS@", HERE)
    d = directives(text)
    shutil.rmtree(opts.work, ignore_errors=True)
    os.makedirs(opts.work)
    failures = []

    ranks_list = [int(r) for r in d.get("test-ranks", "1").split(",")]
    outputs = []
    for ranks in ranks_list:
        out_dir = os.path.join(opts.work, f"ranks-{ranks}")
        prm_copy = os.path.join(opts.work, f"{name}-ranks-{ranks}.prm")
        with open(prm_copy, "w") as f:
            # A later 'set' overrides an earlier one: redirect the output.
            f.write(text + f"\nsubsection Output\n  set Directory = {out_dir}\nend\n")
        args = d["test-args"].replace("@TESTS@", HERE).split() if "test-args" in d else [prm_copy]
        result = run(opts.executable, args, ranks, opts.work)
        sys.stdout.write(result.stdout[-4000:])
        sys.stderr.write(result.stderr[-4000:])

        runtime = "test-expect-runtime-error" in d
        if "test-expect-error" in d or runtime:
            expected = d["test-expect-runtime-error" if runtime else "test-expect-error"]
            if result.returncode == 0:
                failures.append("the run succeeded, but it should have failed")
            if expected not in result.stderr:
                failures.append(f"stderr does not contain {expected!r}")
            if len([l for l in result.stderr.splitlines() if l.startswith("fdparticle: error")]) != 1:
                failures.append("expected exactly one 'fdparticle: error' line")
            if os.path.exists(out_dir) and not runtime:
                failures.append(f"output directory {out_dir} was created despite the error")
            continue
        if result.returncode != 0:
            failures.append(f"fdparticle exited with {result.returncode}")
            continue
        outputs.append(out_dir)

        if "test-compare" in d:
            rel, abs_tol = (float(x) for x in d.get("test-tolerance", "1e-6 1e-10").split())
            for fname in d["test-compare"].split():
                expected = os.path.join(HERE, name, fname)
                actual = os.path.join(out_dir, fname)
                if not os.path.exists(actual):
                    failures.append(f"{fname} was not written")
                    continue
                if not os.path.exists(expected):
                    failures.append(f"no stored {expected}; to create it: cp {actual} {expected}")
                    continue
                failures += compare_csv(actual, expected, rel, abs_tol)
        if "test-restart-at" in d:
            failures += check_restart(opts, text, d, ranks, out_dir)
        if "test-check" in d:
            script, *check_args = d["test-check"].split()
            script = os.path.join(HERE, script)
            check = subprocess.run([sys.executable, script, out_dir] + check_args,
                                   capture_output=True, text=True,
                                   env=dict(os.environ, PYTHONPATH=HERE))
            sys.stdout.write(check.stdout)
            sys.stderr.write(check.stderr)
            if check.returncode != 0:
                failures.append(f"check {d['test-check']} failed")  # noqa

    if len(outputs) > 1:
        tol = float(d.get("test-rank-tolerance", "1e-8"))
        base = os.path.join(outputs[0], "particles.csv")
        for other in outputs[1:]:
            # Relative agreement; the absolute floor only absorbs round-off around zero.
            for p in compare_csv(os.path.join(other, "particles.csv"), base, tol, 1e-12):
                failures.append(f"{os.path.basename(other)} vs {os.path.basename(outputs[0])}: {p}")

    for f in failures[:30]:
        print("FAIL:", f)
    if failures:
        print(f"{name}: {len(failures)} failure(s)")
        return 1
    print(f"{name}: passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
