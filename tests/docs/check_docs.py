#!/usr/bin/python3
"""The documentation says what the program and the suite are.

Fails when
- doc/parameters.md differs from what scripts/parameter-reference.py writes from the
  program's declarations (regenerate it with the command the failure prints);
- a CSV file the program writes is not documented in README.md with its exact header
  line, or one of its columns is not named in README.md's Output section;
- tests/README.md does not give the number of tests ctest has, or does not name one of
  them.
"""
import argparse
import difflib
import os
import re
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from testlib import check, finish  # noqa: E402

# A 2D scene with one free particle, one Stokes step: it writes every CSV file a run writes.
SCENE = """set Dimension = 2
set Gravity = 0, -10
subsection Geometry
  set Lower corner = 0, 0
  set Upper corner = 1, 2
  set Subdivisions = 4, 8
end
subsection Fluid
  set Convection = false
end
subsection Particles
  set Particles = 0.5, 1 : 0.15 : 1.5
end
subsection Time
  set Time step = 0.05
  set End time = 0.05
end
subsection Output
  set Directory = output
  set VTU interval = 0
end
"""


def check_parameter_reference(source, executable):
    script = os.path.join(source, "scripts", "parameter-reference.py")
    generated = subprocess.run([sys.executable, script, executable], check=True,
                               capture_output=True, text=True).stdout
    path = os.path.join(source, "doc", "parameters.md")
    stored = open(path).read() if os.path.exists(path) else ""
    same = generated == stored
    if not same:
        sys.stdout.writelines(difflib.unified_diff(
            stored.splitlines(True), generated.splitlines(True),
            "doc/parameters.md (checked in)", "doc/parameters.md (from the program)"))
        print("regenerate: scripts/parameter-reference.py build/fdparticle > doc/parameters.md")
    check(same, "doc/parameters.md is what the program declares")


def output_section(readme):
    match = re.search(r"^## Output\n(.*?)(?=^## )", readme, re.S | re.M)
    return match.group(1) if match else ""


def check_csv_columns(source, executable, work):
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    with open(os.path.join(work, "scene.prm"), "w") as f:
        f.write(SCENE)
    subprocess.run([executable, "scene.prm"], cwd=work, check=True, stdout=subprocess.DEVNULL)
    readme = open(os.path.join(source, "README.md")).read()
    section = output_section(readme)
    check(section != "", "README.md has an '## Output' section")
    out_dir = os.path.join(work, "output")
    csv_files = sorted(f for f in os.listdir(out_dir) if f.endswith(".csv"))
    check(len(csv_files) >= 3, "the scene wrote its CSV files (%s)" % ", ".join(csv_files))
    for name in csv_files:
        with open(os.path.join(out_dir, name)) as f:
            header = f.readline().strip()
        check("`%s`" % header in section,
              "README.md's Output section gives the header of %s: %s" % (name, header))
        missing = [c for c in header.split(",") if "`%s`" % c not in section]
        check(not missing, "README.md's Output section names every column of %s%s"
              % (name, " (missing: %s)" % ", ".join(missing) if missing else ""))


def check_test_list(source, build):
    listing = subprocess.run(["ctest", "-N"], cwd=build, check=True, capture_output=True,
                             text=True).stdout
    names = re.findall(r"^\s*Test\s+#\d+: (\S+)", listing, re.M)
    text = open(os.path.join(source, "tests", "README.md")).read()
    count = re.search(r"The whole suite \((\d+) tests\)", text)
    check(count is not None and int(count.group(1)) == len(names),
          "tests/README.md gives the number of tests: %s, ctest has %d"
          % (count.group(1) if count else "(no 'The whole suite (N tests)')", len(names)))
    missing = [n for n in names if "`%s`" % n not in text]
    check(not missing, "tests/README.md names every test%s"
          % (" (missing: %s)" % ", ".join(missing) if missing else ""))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--executable", required=True)
    parser.add_argument("--source", required=True, help="the repository's top directory")
    parser.add_argument("--build", required=True, help="the build directory ctest runs in")
    parser.add_argument("--work", required=True)
    args = parser.parse_args()
    executable = os.path.abspath(args.executable)
    check_parameter_reference(args.source, executable)
    check_csv_columns(args.source, executable, args.work)
    check_test_list(args.source, args.build)
    finish()


if __name__ == "__main__":
    main()
