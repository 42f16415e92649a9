#!/usr/bin/python3
"""ctest blas_kernels: the program runs with the BLAS kernels of the CPU it runs on.

OpenBLAS falls back to its Prescott (SSE3) kernels on a CPU it does not know, four to six
times slower for dense products than its AVX2 or AVX-512 kernels; fdparticle then starts
itself anew with OPENBLAS_CORETYPE set (BlasKernels, doc/performance.md "The BLAS
kernels"). Checks, from `fdparticle --version`:
  - without OPENBLAS_CORETYPE, on a CPU with AVX2 and FMA, the kernels are not Prescott;
  - a user's OPENBLAS_CORETYPE is kept (Prescott asked, Prescott run);
  - the restarted program has its arguments: a one-step run writes its output.
Where the BLAS is not OpenBLAS there is nothing to choose and the test passes.

Usage: check_blas_kernels.py --executable build/fdparticle --work DIR
"""
import argparse
import os
import re
import shutil
import subprocess
import sys

SCENE = """set Dimension = 2
set Gravity = 0, -10
subsection Geometry
  set Lower corner = 0, 0
  set Upper corner = 1, 1
  set Subdivisions = 2, 2
end
subsection Particles
  set Particles = 0.5, 0.5 : 0.2 : 1.5
end
subsection Time
  set End time = 0.1
  set Time step = 0.1
end
subsection Output
  set Directory = output
  set VTU interval = 0
end
"""


def blas_line(executable, coretype):
    env = dict(os.environ)
    env.pop("OPENBLAS_CORETYPE", None)
    if coretype:
        env["OPENBLAS_CORETYPE"] = coretype
    out = subprocess.run([executable, "--version"], check=True, capture_output=True, text=True,
                         env=env).stdout
    return next((l for l in out.splitlines() if l.startswith("BLAS: ")), "")


def cpu_flags():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("flags"):
                    return set(line.split(":", 1)[1].split())
    except OSError:
        pass
    return set()


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--executable", required=True)
    parser.add_argument("--work", required=True)
    args = parser.parse_args()
    failures = []

    def check(ok, what):
        print(("ok:   " if ok else "FAIL: ") + what)
        if not ok:
            failures.append(what)

    line = blas_line(args.executable, None)
    check(line != "", "--version names the BLAS: %s" % line)
    if line == "BLAS: not OpenBLAS":
        print("the BLAS is not OpenBLAS: its kernels are not chosen")
        return 0
    kernels = re.match(r"BLAS: OpenBLAS \S+, (\S+) kernels", line)
    check(kernels is not None, "--version names OpenBLAS's kernels: %s" % line)
    flags = cpu_flags()
    if kernels and {"avx2", "fma"} <= flags:
        check(kernels.group(1) != "Prescott",
              "on a CPU with AVX2 and FMA the kernels are not Prescott: %s" % line)
    asked = blas_line(args.executable, "Prescott")
    check(asked == "BLAS: OpenBLAS %s, Prescott kernels (OPENBLAS_CORETYPE)"
          % line.split()[2].rstrip(","),
          "a user's OPENBLAS_CORETYPE is kept: %s" % asked)

    shutil.rmtree(args.work, ignore_errors=True)
    os.makedirs(args.work)
    with open(os.path.join(args.work, "scene.prm"), "w") as f:
        f.write(SCENE)
    env = dict(os.environ)
    env.pop("OPENBLAS_CORETYPE", None)
    run = subprocess.run([args.executable, "scene.prm"], cwd=args.work, env=env,
                         capture_output=True, text=True)
    prm = os.path.join(args.work, "output", "parameters.prm")
    first = open(prm).readline().strip() if os.path.exists(prm) else ""
    check(run.returncode == 0 and first.endswith(line[len("BLAS: "):]),
          "a run started anew keeps its arguments and names the kernels it ran with: %s"
          % (first or run.stderr.strip()[-300:]))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
