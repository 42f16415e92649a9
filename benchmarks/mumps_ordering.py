#!/usr/bin/env python3
"""The direct solver's cost by MUMPS ordering (Solver/MUMPS ordering), 2D and 3D, on 1 rank:
the analysis (ordering + symbolic factorization), the numeric factorization and its flops,
and the whole run, so that 'default' can be checked against the alternatives.

Scenes: the 2D cavity (prm/cavity2d.prm) on uniform meshes of 40^2, 80^2 and 160^2 cells,
3 steps; the 3D sediment (prm/sediment.prm), 3 steps. Writes doc/mumps_ordering.csv (with
the date and the source revision) and prints a Markdown table. Run alone (~6 min):
    /usr/bin/python3 benchmarks/mumps_ordering.py
"""
import argparse
import csv
import datetime
import os
import re
import subprocess
import tempfile
import time

TOP = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def scene(name, cells):
    """The prm text of a scene: 3 steps, no VTU output."""
    if name == "cavity2d":
        text = open(os.path.join(TOP, "prm", "cavity2d.prm")).read()
        text = re.sub(r"set Subdivisions *=.*", f"set Subdivisions = {cells}, {cells}", text)
        text = re.sub(r"set End time *=.*", "set End time = 0.03", text)
    else:
        text = open(os.path.join(TOP, "prm", "sediment.prm")).read()
        text = re.sub(r"set End time *=.*", "set End time = 0.3", text)
    return text


def run(exe, text, ordering, work):
    prm = os.path.join(work, "run.prm")
    with open(prm, "w") as f:
        f.write(text + "\nsubsection Solver\n  set Linear solver = direct\n"
                "  set Direct solver statistics = true\n"
                f"  set MUMPS ordering = {ordering}\nend\n"
                f"subsection Output\n  set Directory = {work}/out\n  set VTU interval = 0\nend\n")
    start = time.time()
    log = subprocess.run([exe, prm], capture_output=True, text=True, check=True).stdout
    seconds = time.time() - start
    symbolic = [float(x) for x in re.findall(r"symbolic factorization ([0-9.]+) s", log)]
    numeric = re.findall(r"numeric factorization ([0-9.]+) s.*?([0-9.e+]+) flops", log)
    with open(os.path.join(work, "out", "statistics.csv")) as f:
        dofs = int(list(csv.DictReader(f))[0]["dofs"])
    return {"dofs": dofs, "run_seconds": round(seconds, 2),
            "analyses": len(symbolic), "analysis_seconds": round(sum(symbolic) / len(symbolic), 3),
            "factorizations": len(numeric),
            "numeric_seconds": round(sum(float(t) for t, _ in numeric) / len(numeric), 3),
            "flops": float(numeric[0][1])}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--executable", default=os.path.join(TOP, "build", "fdparticle"))
    parser.add_argument("--orderings", default="metis,qamd,amf")
    parser.add_argument("--out", default=os.path.join(TOP, "doc", "mumps_ordering.csv"))
    opts = parser.parse_args()
    revision = subprocess.run([opts.executable, "--version"], capture_output=True,
                              text=True).stdout.split()[1]
    date = datetime.date.today().isoformat()
    rows = []
    for name, cells in [("cavity2d", 40), ("cavity2d", 80), ("cavity2d", 160), ("sediment", 0)]:
        for ordering in opts.orderings.split(","):
            with tempfile.TemporaryDirectory() as work:
                row = {"scene": name + (f" {cells}^2" if cells else ""), "ordering": ordering}
                row.update(run(opts.executable, scene(name, cells), ordering, work))
                row.update({"date": date, "revision": revision})
                rows.append(row)
                print(row, flush=True)
    with open(opts.out, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    print("| scene | DoFs | ordering | analysis s | factorization s | flops | run s |")
    print("|---|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['scene']} | {r['dofs']} | {r['ordering']} | {r['analysis_seconds']} | "
              f"{r['numeric_seconds']} | {r['flops']:.3g} | {r['run_seconds']} |")


if __name__ == "__main__":
    main()
