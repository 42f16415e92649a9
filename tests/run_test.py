#!/usr/bin/env python3
"""Run one fdparticle regression/validation test, ASPECT style.

A test is tests/NAME.prm; directives in its comment lines say what to check. Two runs are
compared number by number by one rule (testlib.allowed_difference, tests/README.md):
|a - b| <= REL * max(|a|, |b|) + FLOOR * S, S the largest magnitude of the column's kind
over both runs (positions: the box size); FLOOR defaults to 1e-9.

  # test-ranks: 1, 2               run on each number of MPI ranks (default 1); with several,
                                   particles.csv must agree between them
  # test-rank-tolerance: REL [FLOOR]  (default 1e-8)
  # test-rank-end-time: T          the runs on more ranks than the first end at time T and
                                   are compared with the first run's rows up to T; the
                                   first run alone is checked and varied (test-check,
                                   test-compare, test-variant, ...), except that a
                                   test-solvers run on such a rank count ends at T too
  # test-expect-error: TEXT        the run must fail (non-zero exit), print TEXT on stderr
                                   in one 'fdparticle: error' line, end every rank without
                                   aborting MPI, and leave no output directory behind
  # test-expect-runtime-error: TEXT  the same, but the run may have written output first
  # test-args: ARGS                run 'fdparticle ARGS' instead of 'fdparticle NAME.prm'
                                   (@TESTS@ in ARGS and in the prm: the tests/ directory)
  # test-compare: FILE [FILE ...]  compare output files with tests/NAME/FILE (CSV, numeric,
  # test-tolerance: REL [FLOOR]    default 1e-6 1e-10; wall_seconds is never compared)
  # test-solvers: REL FLOOR [N]    also run the scene with the other Solver/Linear solver
                                   (iterative for a direct scene, direct for an iterative
                                   one), on each number of ranks (or on N ranks only):
                                   particles.csv must agree
  # test-variant: OLD => NEW       also run the scene with the text OLD replaced by NEW
  # test-variant-tolerance: REL [FLOOR]  (on each number of ranks; default 1e-9): a scene
  # test-variant-ignore: COLUMNS   written another way must give the same particles.csv
                                   but for COLUMNS (e.g. a ball written as an ellipsoid of
                                   equal axes, turned: all but its orientation)
  # test-check: SCRIPT [ARGS]      run tests/SCRIPT OUTPUT_DIR [ARGS]; it exits non-zero on failure
  # test-expect-output: N TEXT     the run on N ranks must print TEXT on stdout or stderr
                                   (an event that the scene is built to cause, e.g. a
                                   repartition or a warning)
  # test-restart-at: T             also run to End time T with checkpoints, then resume
                                   (Checkpointing/Resume = true) to the End time of the
                                   prm, after mimicking a kill during the last checkpoint
                                   write (only checkpoint.old and a partial checkpoint.new
                                   left); particles.csv and the step rows of
                                   statistics.csv must equal those of the uninterrupted
  # test-restart-tolerance: REL FLOOR  run (default 1e-12 1e-14)
  # test-mirror: AXIS[, AXIS]      also run the scene mirrored across the mid-plane of the
  # test-mirror-tolerance: TOL     box normal to AXIS (x, y or z: particle positions,
                                   Gravity, Body force, wall velocities and prescribed
                                   motions mirrored, the faces AXIS- and AXIS+ swapped);
                                   particles.csv and the mean velocities in statistics.csv
                                   must be the mirror images of the first run's, to TOL
                                   (default 1e-10) relative to the largest value of each
                                   kind of column (positions: the box size). A scene that
                                   is its own mirror image must so stay symmetric.
  # test-shift: AXIS DISTANCE[, AXIS DISTANCE]  also run the scene with every particle
  # test-shift-tolerance: TOL      moved by DISTANCE along the periodic direction AXIS (its
                                   centre wrapped into the box; one run per pair): the
                                   flow is the same, shifted, so
                                   particles.csv and the mean velocities in statistics.csv
                                   must equal the first run's (positions modulo the period)
                                   to TOL (default 1e-10) relative to the largest value of
                                   each kind of column. DISTANCE must be a whole number of
                                   cells, so that the mesh moves onto itself.

Every run, whatever its directives: its linear solver set up (factored or built a
preconditioner) at most once per Jacobian in each step (statistics.csv).

The output directory set in the prm is replaced by --work/ranks-N.
"""
import argparse
import csv
import os
import re
import shutil
import subprocess
import sys
import tempfile

import testlib

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


def compare_csv(actual, expected, rel, floor, box=None, ignored=(), until=None):
    """Mismatches (empty: the files agree) of two CSV files, value by value, by the rule of
    testlib: |a - b| <= rel * max(|a|, |b|) + floor * S, S the scale of the column's kind
    over both files (positions: box, when given). With until, the rows of both files up to
    that time."""
    ha, ra = read_csv(actual)
    he, re_ = read_csv(expected)
    if until is not None:
        ra = [r for r in ra if float(r[ha.index("time")]) <= until * (1 + 1e-12)]
        re_ = [r for r in re_ if float(r[he.index("time")]) <= until * (1 + 1e-12)]
    # Columns added to a table later do not break stored output; missing ones do.
    missing = [h for h in he if h not in ha]
    if missing:
        return [f"{os.path.basename(actual)}: columns {missing} missing (header {ha})"]
    ra = [[row[ha.index(h)] for h in he] for row in ra]
    ha = he
    if len(ra) != len(re_):
        return [f"{os.path.basename(actual)}: {len(ra)} rows, expected {len(re_)}"]
    radii = [float(row[ha.index("radius")]) for row in ra + re_] if "radius" in ha else []
    scales = testlib.column_scales(ha, [ra, re_], box, min(radii, default=None))
    problems = []
    for i, (a_row, e_row) in enumerate(zip(ra, re_)):
        for name, a_text, e_text in zip(ha, a_row, e_row):
            if name in IGNORED_COLUMNS or name in ignored:
                continue
            a, e = float(a_text), float(e_text)
            # One printed unit apart is round-off; the two decimal values, read back as
            # doubles, differ by that unit only to about 1e-4 of it.
            allowed = max(testlib.allowed_difference(a, e, rel, floor, scales[name]),
                          1.001 * testlib.printed_unit(a_text),
                          1.001 * testlib.printed_unit(e_text))
            if not abs(a - e) <= allowed * (1 + 1e-9):
                problems.append(f"{os.path.basename(actual)} row {i + 1} column {name}: "
                                f"{a!r} vs expected {e!r} (scale {scales[name]:.3g})")
    return problems


def tolerances(text, default):
    """(REL, FLOOR) of a tolerance directive's value; FLOOR defaults to testlib.FLOOR."""
    values = [float(x) for x in (text or default).split()[:2]]
    return values[0], values[1] if len(values) > 1 else testlib.FLOOR


def run_box(out_dir):
    """The box size of the run written to out_dir (its parameters.prm)."""
    return testlib.box_size(testlib.parameters(out_dir))


MPIRUN = os.path.join(os.path.dirname(HERE), "scripts", "mpirun.sh")


def run(executable, args, ranks, cwd):
    # Several ranks through scripts/mpirun.sh: not pinned to cores, idle ranks yield their
    # core (ctest runs other tests beside an MPI run).
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    cmd = [executable] + args
    with tempfile.TemporaryDirectory(prefix="fdparticle-mpi-",
                                     ignore_cleanup_errors=True) as mpi_tmp:
        if ranks > 1:
            cmd = ["bash", MPIRUN, str(ranks)] + cmd
        else:
            # A run without mpirun starts no Open MPI daemon (it never spawns processes).
            # Such runs all take the same job name, so each gets Open MPI's temporary
            # directory of its own: concurrent runs sharing one remove it under each other
            # as they end.
            env["OMPI_MCA_ess_singleton_isolated"] = "1"
            env["OMPI_MCA_orte_tmpdir_base"] = mpi_tmp
        print("running:", " ".join(cmd), flush=True)
        return subprocess.run(cmd, cwd=cwd, env=env, capture_output=True, text=True)


AXES = testlib.AXES
# Of the vector columns of testlib.VECTOR_FAMILIES, the pseudovectors: a mirror normal to
# axis a negates component a of a vector and the other components of a pseudovector.
PSEUDO_COLUMNS = {"w": "angular velocity", "t": "torque", "rot": "rotation"}


def split_column(name):
    """('v', 'x') for 'vx', ('contact_f', 'y') for 'contact_fy', ('position', 'x') for 'x',
    None for a scalar column (testlib.column_family)."""
    family = testlib.column_family(name)
    if family == "position":
        return family, name
    if family in testlib.VECTOR_FAMILIES:
        return family, name[-1]
    return None


def mirror_vector(text, a):
    values = [float(v) for v in text.split(",")]
    values[a] = -values[a]
    return ", ".join(repr(v) for v in values)


def box_range(entries, a, directive):
    """The box's lower and upper coordinate along axis a."""
    if "Geometry/Lower corner" not in entries or "Geometry/Upper corner" not in entries:
        raise SystemExit(f"{directive} needs Geometry/Lower corner and Upper corner in the prm")
    return (float(entries["Geometry/Lower corner"].split(",")[a]),
            float(entries["Geometry/Upper corner"].split(",")[a]))


def moved_particles(entries, a, move, transform_fields=None):
    """The Particles/Particles entries with coordinate a of each centre mapped by move
    (and the fields after the centre by transform_fields), and their radii."""
    particles, radii = [], []
    for entry in entries.get("Particles/Particles", "").split(";"):
        if not entry.strip():
            continue
        fields = [f.strip() for f in entry.split(":")]
        centre = [float(v) for v in fields[0].split(",")]
        centre[a] = move(centre[a])
        radii.append(float(fields[1]))
        fields[0] = ", ".join(repr(v) for v in centre)
        if transform_fields:
            transform_fields(fields)
        particles.append(" : ".join(fields))
    # Later 'set' lines override earlier ones.
    return "\nsubsection Particles\n  set Particles = " + "; ".join(particles) + "\nend\n", radii


def mirror_prm(text, axis):
    """The prm text of the scene mirrored across the box's mid-plane normal to axis."""
    a = AXES.index(axis)
    entries = testlib.prm_entries(text)
    lo, hi = box_range(entries, a, "test-mirror")
    dim = int(entries.get("Dimension", "3"))

    def mirror_motion(fields):
        if len(fields) > 4:  # prescribed: a velocity, and maybe an angular velocity
            fields[4] = mirror_vector(fields[4], a)
            if len(fields) > 5:
                w = [float(v) for v in fields[5].split(",")]
                if dim == 2:
                    w = [-w[0]]
                else:
                    w = [wi if i == a else -wi for i, wi in enumerate(w)]
                fields[5] = ", ".join(repr(v) for v in w)

    extra, radii = moved_particles(entries, a, lambda x: lo + hi - x, mirror_motion)
    walls = []
    for entry in entries.get("Boundary conditions/Wall velocities", "").split(";"):
        if not entry.strip():
            continue
        face, vector = (x.strip() for x in entry.split(":", 1))
        if face[0] == axis:
            face = axis + ("+" if face[1] == "-" else "-")
        walls.append(f"{face}: {mirror_vector(vector, a)}")
    extra += "subsection Boundary conditions\n  set Wall velocities = " + "; ".join(walls) + "\nend\n"
    if "Gravity" in entries:
        extra += "set Gravity = " + mirror_vector(entries["Gravity"], a) + "\n"
    if entries.get("Fluid/Body force", "").strip():
        extra += "subsection Fluid\n  set Body force = " + mirror_vector(entries["Fluid/Body force"], a) + "\nend\n"
    return text + extra, lo, hi, min(radii, default=hi - lo)


def compare_transformed(first_dir, other_dir, label, expected_value, box_size, radius, tol):
    """Mismatches between a run and the run of a transformed scene (a mirror image, a
    periodic shift): expected_value(family, component, value) returns what the first run's
    value should be, given the other run's, and the period modulo which the error counts
    (None: none); box_size sets the scale of positions."""
    problems = []
    velocity_scale = 0.0  # of the particles, for the box's mean velocity (nearly zero in a closed box)
    for fname in ("particles.csv", "statistics.csv"):
        header, rows = read_csv(os.path.join(first_dir, fname))
        header_m, rows_m = read_csv(os.path.join(other_dir, fname))
        if header != header_m or len(rows) != len(rows_m):
            problems.append(f"{fname}: the {label} run has other columns or rows")
            continue
        kinds = {h: split_column(h) for h in header}
        if fname == "statistics.csv":
            kinds = {h: k for h, k in kinds.items()
                     if k and k[0] in ("mean_v", "mean_particle_v")}
        scale = testlib.column_scales(header, [rows, rows_m], max(box_size),
                                      radius if fname == "particles.csv" else None)
        if fname == "particles.csv":
            velocity_scale = scale.get("vx", 0.0)
        else:
            # The box's mean velocity (nearly zero in a closed box) against the particles'.
            scale = {h: max(s, velocity_scale) for h, s in scale.items()}
        for i, h in enumerate(header):
            if not kinds.get(h):
                continue
            family, component = kinds[h]
            c = AXES.index(component)
            for r, (row, row_m) in enumerate(zip(rows, rows_m)):
                x = float(row[i])
                expected, period = expected_value(family, c, float(row_m[i]))
                error = x - expected
                if period:
                    error -= period * round(error / period)
                if abs(error) > tol * max(scale[h], 1e-300):
                    problems.append(f"{label}: {fname} row {r + 1} column {h}: {x!r} vs "
                                    f"{expected!r} from the {label} run (scale {scale[h]:.3g})")
    return problems


def compare_mirrored(first_dir, mirror_dir, axis, lo, hi, radius, tol):
    """Mismatches between a run and the run of its mirror image."""
    a = AXES.index(axis)

    def expected_value(family, c, y):
        if family == "position":
            return (lo + hi - y if c == a else y), None
        if family in PSEUDO_COLUMNS:
            return (y if c == a else -y), None
        return (-y if c == a else y), None

    return compare_transformed(first_dir, mirror_dir, f"mirror {axis}", expected_value,
                               [hi - lo], radius, tol)


def shift_prm(text, axis, distance):
    """The prm text of the scene with every particle moved by distance along axis, its
    centre wrapped into the box; also the box's size along axis and the smallest radius."""
    a = AXES.index(axis)
    entries = testlib.prm_entries(text)
    lo, hi = box_range(entries, a, "test-shift")
    if axis not in entries.get("Geometry/Periodic directions", ""):
        raise SystemExit(f"test-shift needs {axis} among Geometry/Periodic directions")
    extra, radii = moved_particles(entries, a, lambda x: lo + (x + distance - lo) % (hi - lo))
    return text + extra, hi - lo, min(radii, default=hi - lo)


def compare_shifted(first_dir, shifted_dir, axis, distance, period, radius, tol):
    """Mismatches between a run and the run of the scene shifted along a periodic axis."""
    a = AXES.index(axis)

    def expected_value(family, c, y):
        if family == "position" and c == a:
            return y - distance, period
        return y, None

    return compare_transformed(first_dir, shifted_dir, f"shift {axis}", expected_value,
                               [period], radius, tol)


def run_variant(opts, prm_text, name, ranks, suffix):
    """Run a variant of the scene, given as its prm text, into ranks-N-SUFFIX: the output
    directory and the exit code."""
    v_dir = os.path.join(opts.work, f"ranks-{ranks}-{suffix}")
    v_prm = os.path.join(opts.work, f"{name}-ranks-{ranks}-{suffix}.prm")
    with open(v_prm, "w") as f:
        f.write(prm_text + f"\nsubsection Output\n  set Directory = {v_dir}\nend\n")
    result = run(opts.executable, [v_prm], ranks, opts.work)
    sys.stdout.write(result.stdout[-2000:])
    sys.stderr.write(result.stderr[-2000:])
    return v_dir, result.returncode


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
    rel, floor = tolerances(d.get("test-restart-tolerance"), "1e-12 1e-14")
    for p in compare_csv(os.path.join(part_dir, "particles.csv"),
                         os.path.join(full_dir, "particles.csv"), rel, floor, run_box(full_dir)):
        problems.append(f"restarted vs uninterrupted: {p}")
    steps = [read_csv(os.path.join(x, "statistics.csv"))[1] for x in (part_dir, full_dir)]
    if [r[0] for r in steps[0]] != [r[0] for r in steps[1]]:
        problems.append("restarted statistics.csv has other steps than the uninterrupted one")
    return problems


def check_setups(out_dir):
    """Every run: the linear solver factors a matrix or builds a preconditioner at most once
    per Jacobian (statistics.csv: solver_setups <= jacobians in each step); a preconditioner
    rebuilt for the matrix it was built for is wasted work."""
    path = os.path.join(out_dir, "statistics.csv")
    if not os.path.exists(path):
        return []
    header, rows = read_csv(path)
    if "solver_setups" not in header:
        return ["statistics.csv has no solver_setups column"]
    s, j = header.index("solver_setups"), header.index("jacobians")
    return [f"{os.path.basename(out_dir)} step {r[0]}: {r[s]} solver setups for {r[j]} Jacobians"
            for r in rows if float(r[s]) > float(r[j])]


def check_other_solver(opts, text, d, name, ranks, first_dir):
    """Run the scene with the other linear solver; mismatches of particles.csv."""
    entries = testlib.prm_entries(text)
    other = "direct" if entries.get("Solver/Linear solver") == "iterative" else "iterative"
    o_dir, code = run_variant(opts, text + f"\nsubsection Solver\n  set Linear solver = {other}\nend\n",
                              name, ranks, other)
    if code != 0:
        return [f"the run with the {other} solver exited with {code}"]
    rel, floor = tolerances(d["test-solvers"], None)
    return [f"{other} solver: {p}" for p in
            compare_csv(os.path.join(o_dir, "particles.csv"),
                        os.path.join(first_dir, "particles.csv"), rel, floor,
                        run_box(first_dir)) +
            check_setups(o_dir)]


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
    rank_end_time = float(d["test-rank-end-time"]) if "test-rank-end-time" in d else None
    outputs = []
    for ranks in ranks_list:
        out_dir = os.path.join(opts.work, f"ranks-{ranks}")
        prm_copy = os.path.join(opts.work, f"{name}-ranks-{ranks}.prm")
        shortened = rank_end_time is not None and ranks != ranks_list[0]
        # A later 'set' overrides an earlier one: shorten the run, redirect the output.
        scene = text + (f"\nsubsection Time\n  set End time = {rank_end_time!r}\nend\n"
                        if shortened else "")
        with open(prm_copy, "w") as f:
            f.write(scene + f"\nsubsection Output\n  set Directory = {out_dir}\nend\n")
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
            # An error every rank knows must end each rank normally, not abort MPI.
            if "MPI_ABORT" in result.stderr or "fdparticle: error on rank" in result.stderr:
                failures.append("the error aborted MPI instead of ending every rank normally")
            if os.path.exists(out_dir) and not runtime:
                failures.append(f"output directory {out_dir} was created despite the error")
            continue
        if result.returncode != 0:
            failures.append(f"fdparticle exited with {result.returncode}")
            continue
        outputs.append(out_dir)
        failures += check_setups(out_dir)
        if "test-expect-output" in d:
            on_ranks, expected = d["test-expect-output"].split(None, 1)
            if int(on_ranks) == ranks and expected not in result.stdout + result.stderr:
                failures.append(f"the output on {ranks} rank(s) does not contain {expected!r}")
        solver_ranks = d.get("test-solvers", "").split()[2:]
        if "test-solvers" in d and (not solver_ranks or str(ranks) in solver_ranks):
            failures += check_other_solver(opts, scene, d, name, ranks, out_dir)
        if shortened:
            continue

        if "test-compare" in d:
            rel, floor = tolerances(d.get("test-tolerance"), "1e-6 1e-10")
            for fname in d["test-compare"].split():
                expected = os.path.join(HERE, name, fname)
                actual = os.path.join(out_dir, fname)
                if not os.path.exists(actual):
                    failures.append(f"{fname} was not written")
                    continue
                if not os.path.exists(expected):
                    failures.append(f"no stored {expected}; to create it: cp {actual} {expected}")
                    continue
                failures += compare_csv(actual, expected, rel, floor, run_box(out_dir))
        if "test-restart-at" in d:
            failures += check_restart(opts, text, d, ranks, out_dir)
        if "test-mirror" in d:
            tol = float(d.get("test-mirror-tolerance", "1e-10"))
            for axis in (x.strip() for x in d["test-mirror"].split(",")):
                mirrored, lo, hi, radius = mirror_prm(text, axis)
                m_dir, code = run_variant(opts, mirrored, name, ranks, f"mirror-{axis}")
                if code != 0:
                    failures.append(f"the run mirrored in {axis} exited with {code}")
                    continue
                failures += compare_mirrored(out_dir, m_dir, axis, lo, hi, radius, tol)
        for shift in (s.split() for s in d.get("test-shift", "").split(",") if s.strip()):
            axis, distance = shift[0], float(shift[1])
            tol = float(d.get("test-shift-tolerance", "1e-10"))
            shifted, period, radius = shift_prm(text, axis, distance)
            s_dir, code = run_variant(opts, shifted, name, ranks, f"shift-{axis}")
            if code != 0:
                failures.append(f"the run shifted in {axis} exited with {code}")
                continue
            failures += compare_shifted(out_dir, s_dir, axis, distance, period, radius, tol)
        if "test-variant" in d:
            old_text, _, new_text = d["test-variant"].partition("=>")
            if old_text.strip() not in text:
                failures.append(f"test-variant: {old_text.strip()!r} is not in the prm")
            else:
                v_dir, code = run_variant(opts, text.replace(old_text.strip(), new_text.strip()),
                                          name, ranks, "variant")
                if code != 0:
                    failures.append(f"the variant run exited with {code}")
                else:
                    rel, floor = tolerances(d.get("test-variant-tolerance"), "1e-9")
                    ignored = d.get("test-variant-ignore", "").split()
                    failures += [f"variant: {p}" for p in
                                 compare_csv(os.path.join(v_dir, "particles.csv"),
                                             os.path.join(out_dir, "particles.csv"), rel, floor,
                                             run_box(out_dir), ignored)]
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
        rel, floor = tolerances(d.get("test-rank-tolerance"), "1e-8")
        base = os.path.join(outputs[0], "particles.csv")
        for other in outputs[1:]:
            for p in compare_csv(os.path.join(other, "particles.csv"), base, rel, floor,
                                 run_box(outputs[0]), until=rank_end_time):
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
