#!/usr/bin/python3
"""ctest plot_tool_2d: tools/fdparticle-plot draws a run.

Runs a tiny 2D scene (two disks, Stokes, 4 x 8 cells, 3 steps, about a second) into the
work directory and plots it; then plots two written outputs: a 3D run of 20 particles
without the statistics columns min_gap and contacts whose last line was cut off (a run
that ended early), and a directory with statistics.csv only. Checks:
  - exit status 0 and the PNGs trajectories, velocities, forces, gaps (when min_gap is
    there) and steps exist and are PNG files of some size;
  - a missing directory and one without output fail with exactly one line
    'fdparticle-plot: error: ...' on stderr (no traceback).

Usage: check_plot.py --tool tools/fdparticle-plot --executable build/fdparticle --work DIR
"""
import argparse
import math
import os
import shutil
import subprocess
import sys

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
  set Particles = 0.3, 1 : 0.12 : 1.5; 0.7, 1.3 : 0.12 : 2
end
subsection Time
  set Time step = 0.05
  set End time = 0.15
end
subsection Output
  set Directory = output
  set VTU interval = 0
end
"""
PARTICLE_HEADER = ("time,id,x,y,z,vx,vy,vz,wx,wy,wz,fx,fy,fz,tx,ty,tz,"
                   "contact_fx,contact_fy,contact_fz,radius")
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from testlib import check, failed  # noqa: E402


def plot(tool, directory, *options):
    res = subprocess.run([sys.executable, tool, directory, *options], capture_output=True, text=True)
    print(res.stdout + res.stderr, end="")
    return res


def check_pngs(directory, names, what):
    for name in names:
        path = os.path.join(directory, name + ".png")
        ok = os.path.isfile(path) and os.path.getsize(path) > 5000
        if ok:
            with open(path, "rb") as f:
                ok = f.read(8) == b"\x89PNG\r\n\x1a\n"
        check(ok, f"{what}: {name}.png is a non-empty PNG")


def check_error(res, what):
    lines = res.stderr.strip().splitlines()
    check(res.returncode != 0 and len(lines) == 1 and lines[0].startswith("fdparticle-plot: error: ")
          and "Traceback" not in res.stderr, f"{what}: one error line and a non-zero exit status")


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--tool", required=True)
    p.add_argument("--executable", required=True)
    p.add_argument("--work", required=True)
    args = p.parse_args()
    args.executable = os.path.abspath(args.executable)
    if os.path.isdir(args.work):
        shutil.rmtree(args.work)
    os.makedirs(args.work)

    # A real 2D run with two particles.
    with open(os.path.join(args.work, "scene.prm"), "w") as f:
        f.write(SCENE)
    run = subprocess.run([args.executable, "scene.prm"], cwd=args.work, capture_output=True, text=True)
    if not check(run.returncode == 0, "the 2D scene runs"):
        print(run.stderr)
        return 1
    out = os.path.join(args.work, "output")
    res = plot(args.tool, out)
    check(res.returncode == 0, "2D run: exit status 0")
    check_pngs(out, ["trajectories", "velocities", "forces", "gaps", "steps"], "2D run")
    res = plot(args.tool, out, "--output", os.path.join(args.work, "pngs"))
    check_pngs(os.path.join(args.work, "pngs"), ["trajectories", "steps"], "--output DIR")

    # A 3D run of 20 particles that ended early, statistics.csv without min_gap, contacts.
    synthetic = os.path.join(args.work, "synthetic_3d")
    os.makedirs(synthetic)
    with open(os.path.join(synthetic, "particles.csv"), "w") as f:
        f.write(PARTICLE_HEADER + "\n")
        for step in range(6):
            t = 0.1 * step
            for i in range(20):
                x, y, z = 0.1 + 0.04 * i, 1 - 0.05 * t * (1 + i % 3), 0.5 + 0.01 * math.sin(i + t)
                f.write(f"{t},{i},{x},{y},{z},0,{-0.05 * (1 + i % 3)},0.001,0.01,0,0.02,"
                        f"0.1,{-0.2 - 0.01 * i},0.01,0,0,0,0,0,0,0.02\n")
        f.write("0.6,0,0.1,0.9")  # cut off
    with open(os.path.join(synthetic, "statistics.csv"), "w") as f:
        f.write("step,time,dt,cells,dofs,nonlinear_iterations,linear_iterations,wall_seconds\n")
        for step in range(1, 6):
            f.write(f"{step},{0.1 * step},0.1,512,9000,3,{40 + step},{1.5 + 0.1 * step}\n")
    res = plot(args.tool, synthetic)
    check(res.returncode == 0, "3D, 20 particles, ended early: exit status 0")
    check_pngs(synthetic, ["trajectories", "velocities", "forces", "steps"], "3D, 20 particles")
    check(not os.path.exists(os.path.join(synthetic, "gaps.png")), "no min_gap column: no gaps.png")

    # statistics.csv only.
    only_stats = os.path.join(args.work, "statistics_only")
    os.makedirs(only_stats)
    shutil.copy(os.path.join(synthetic, "statistics.csv"), only_stats)
    res = plot(args.tool, only_stats)
    check(res.returncode == 0, "statistics.csv only: exit status 0")
    check_pngs(only_stats, ["steps"], "statistics.csv only")

    check_error(plot(args.tool, os.path.join(args.work, "does-not-exist")), "a missing directory")
    os.makedirs(os.path.join(args.work, "empty"))
    check_error(plot(args.tool, os.path.join(args.work, "empty")), "a directory without output")

    print(f"{failed()} check(s) failed" if failed() else "all checks passed")
    return 1 if failed() else 0


if __name__ == "__main__":
    sys.exit(main())
