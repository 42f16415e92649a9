#!/usr/bin/python3
"""Randomized parallel-consistency check: the same scene on 1, 2 and 3 MPI ranks must give
the same particles.csv, number by number.

Each scene is drawn from (--seed, scene index): 2D or 3D box, 1-3 balls (non-overlapping,
clear of the walls, anywhere along a periodic direction), their densities and motion, base
mesh, Global refinements, Particle refinement levels (--levels, 0-2), Stokes or
Navier-Stokes, periodic directions, cut-cell rule, time step, scheme and solver options,
the contact model between balls (none, repulsion, spring-dashpot with or without friction)
and lubrication, and a number of steps (--steps, --steps-3d). It is written as
WORK/scene-K/scene.prm and run on every rank count of --ranks (oversubscribed mpirun
beyond 1). A scene fails when

  - a rank count crashes, hangs (no output for STALL_SECONDS, or --timeout) or stops with
    an error, unless every rank count stops with the same error (then the scene itself is
    at fault: also a failure, reported as such, since the generator should only make
    valid scenes);
  - particles.csv or statistics.csv holds a NaN or inf;
  - the step times, cells or DoFs in statistics.csv differ between rank counts;
  - a number in particles.csv differs from the first rank count's by more than
    REL_TOL * max(|a|, |b|) + FLOOR * scale, scale the largest value of that kind of
    column in the scene (tests/testlib.py: positions against the box size; angular
    velocities and torques also against what the translation makes of them on the
    smallest ball).

Adaptive meshes repartition the cells at every adaptation, so scenes with Particle
refinement levels >= 1 and a few dozen steps exercise the layouts that change between
steps: this is where a parallel vector once kept its previous partition.

Run from the top of the repository, after building:
    /usr/bin/python3 benchmarks/parallel_consistency.py --seed 1 --scenes 20
Reproduce one scene (its prm is kept when it fails):
    /usr/bin/python3 benchmarks/parallel_consistency.py --prm WORK/scene-K/scene.prm
Exit status: 0 when every scene passes, 1 otherwise.
"""
import argparse
import csv
import math
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import time

TOP = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(TOP, "tests"))
from testlib import FLOOR, allowed_difference, column_scales, prm_entries  # noqa: E402  (after the path it lives on)

REL_TOL = 1e-8
# Values far below the largest of their kind are compared against testlib.FLOOR of that
# (tests/README.md). The rank counts solve with other orderings, so their solutions differ
# by the solver's residual (up to the Nonlinear tolerance), in proportion to the whole
# solution: a slow rotation next to a fast translation differed by 1e-8 of itself but
# 1e-10 of v/R (KLU on 1 and 2 ranks, Newton residuals 1e-11 and 5e-13).
FLOOR_FRACTION = FLOOR / REL_TOL
TIME_REL_TOL = 1e-12
IGNORED_COLUMNS = {"wall_seconds"}
# statistics.csv columns that depend on the mesh and the step sequence only.
MESH_COLUMNS = ("time", "dt", "cells", "dofs")
AXES = "xyz"

# Scene ranges. Small meshes: every scene runs once per rank count, oversubscribed. On 2
# busy cores, 1, 2 and 3 ranks together took 75 s for 3 steps of a 3D scene with 4 x 4 x 4
# cells and one refinement level, and 79 s for 4 steps of a 2D one with 16 x 32 cells, two
# levels and 3 balls.
BOX_HEIGHTS = (1.0, 1.5, 2.0)              # width 1 (and depth 1 in 3D)
CELLS_PER_UNIT = {2: (4, 6, 8), 3: (2, 3)}
MAX_CELLS_PER_UNIT = {2: 8, 3: 4}          # after Global refinements
MAX_FINEST_CELLS_PER_UNIT = {2: 32, 3: 6}  # after particle refinement
RADIUS_RANGE = (0.07, 0.18)                # of the box width
MIN_RADIUS_CELLS = 0.5                     # radius >= this many coarse cells
WALL_GAP_CELLS = 1.5                       # finest cells between a ball and a wall
PAIR_GAP_CELLS = 2.0                       # finest cells between two balls
MIN_PAIR_GAP = 0.1
MAX_GAP = 0.2                              # caps the gaps on the coarsest 3D meshes
# Runs up to this end time may stack balls along gravity: too short for their settling
# speeds to close the gap.
SHORT_RUN = 0.5
TIME_STEPS = (0.01, 0.02, 0.025, 0.05, 0.1)
VISCOSITY_RANGE = (0.02, 1.0)              # log-uniform, fluid density 1
# On an adapted mesh the heaviest (or lightest) free ball should cross this many finest
# cells during the run, so that the mesh and its partition change many times: the
# viscosity is drawn below the value that makes its estimated settling speed
# SETTLING_FACTOR |rho_P - rho_f| |g| R^2 / mu too slow for that. The factor underestimates
# 2D runs in a unit-wide box (measured 0.07 and 0.5 for R = 0.13 and 0.09).
TRAVEL_CELLS = 4.0
SETTLING_FACTOR = 0.1
DENSITY_RANGES = ((0.5, 0.9), (1.1, 3.0))  # of the balls; near-neutral excluded
GRAVITY_RANGE = (1.0, 10.0)
LID_SPEED_MAX = 0.3
# Chances of the options a scene draws.
GLOBAL_REFINEMENT_CHANCE = 0.4             # per further refinement
PERIODIC_CHANCE = 0.3                      # per lateral direction
FIXED_CHANCE = 0.1                         # per ball; as many prescribed, the rest free
PRESCRIBED_CHANCE = 0.1
CONVECTION_CHANCE = 0.6                    # Navier-Stokes, else Stokes
KLU_CHANCE = 0.2                           # else MUMPS
# KLU factors a 3D mesh of 18k DoFs (3 x 4 x 3 cells, one level) in 20 s: only coarser.
KLU_MAX_FINEST_CELLS_3D = 4
LID_CHANCE = 0.3
# A prescribed ball moves this many finest cells over the run: it stays clear of the walls.
PRESCRIBED_TRAVEL_CELLS = 0.25
# Between balls: no model (an overlap stops every rank count alike), the repulsion, or
# the spring-dashpot, with Coulomb friction where the angular velocity comes from the
# torque balance (friction needs it). Lubrication acts on gaps below three cells.
CONTACT_MODELS = ("none", "repulsion", "spring-dashpot")
FRICTION_CHANCE = 0.5
FRICTION_RANGE = (0.1, 0.5)
LUBRICATION_CHANCE = 0.3
# With a contact model, this chance that two balls start in contact, at a gap of this many
# finest cells: above half a cell, so that two prescribed balls (each travels a quarter
# cell) cannot meet.
CLOSE_PAIR_CHANCE = 0.6
CLOSE_PAIR_GAP_CELLS = (0.55, 0.9)
GAUSS_POINTS = (3, 5, 7)
# Level-set rules cost 20x the assembly of Gauss rules at order 6 in 3D, 1.5x at order 2.
LEVEL_SET_ORDERS = {2: (3, 4, 6), 3: (2, 3, 4)}
PLACEMENT_ATTEMPTS = 200

# A run that prints no line for this long counts as hung (a layout mismatch between ranks
# can deadlock a collective): every step prints one, and a step of these scenes takes
# seconds, tens of seconds on 3 oversubscribed ranks of a busy machine. The later rank
# counts also get STALL_FACTOR times the longest step of the first one: oversubscribed
# ranks took up to 5 times as long as one rank.
STALL_SECONDS = 180.0
STALL_FACTOR = 10.0
STEP_SECONDS = re.compile(r"DoFs\s+\d+\s+([0-9.eE+-]+) s")
CRASH_LINE = re.compile(r"Signal:|signal \d|Segmentation|free\(\)|terminate called|what\(\)|Abort")
POLL_SECONDS = 1.0
KILL_GRACE = 10.0


def fmt(x):
    return f"{x:.6g}"


def vec(values):
    return ", ".join(fmt(v) for v in values)


# ------------------------------------------------------------------------------ scenes
def choose_mesh(rng, dim, level_range):
    """(box extent, subdivisions, global refinements, particle refinement levels,
    coarse and finest cell size)."""
    height = rng.choice(BOX_HEIGHTS)
    extent = [1.0, height] + ([1.0] if dim == 3 else [])
    per_unit = rng.choice(CELLS_PER_UNIT[dim])
    global_refinements = 0
    while (rng.random() < GLOBAL_REFINEMENT_CHANCE
           and per_unit * 2 ** (global_refinements + 1) <= MAX_CELLS_PER_UNIT[dim]):
        global_refinements += 1
    coarse = per_unit * 2 ** global_refinements
    # The cost cap lowers the highest level, never below the lowest one asked for.
    max_levels = level_range[0]
    while (max_levels < level_range[1]
           and coarse * 2 ** (max_levels + 1) <= MAX_FINEST_CELLS_PER_UNIT[dim]):
        max_levels += 1
    levels = rng.randint(level_range[0], max_levels)
    subdivisions = [max(1, round(per_unit * e)) for e in extent]
    h_coarse = 1.0 / coarse
    return extent, subdivisions, global_refinements, levels, h_coarse, h_coarse / 2 ** levels


def separation(a, b, extent, periodic, axes):
    """Distance of the points a and b over the axes, to the nearest periodic image."""
    return math.hypot(*[(a[d] - b[d]) - (extent[d] * round((a[d] - b[d]) / extent[d])
                                         if periodic[d] else 0.0) for d in axes])


def place_particles(rng, dim, extent, periodic, h_coarse, h_fine, count, stack):
    """Centres and radii, clear of the walls and of each other (to the nearest periodic
    image); in a periodic direction anywhere, a ball may cross the faces. Unless stack,
    laterally apart (across gravity, along -y), so that balls settling at different speeds
    pass each other."""
    wall_gap = min(WALL_GAP_CELLS * h_fine, MAX_GAP)
    pair_gap = max(min(PAIR_GAP_CELLS * h_fine, MAX_GAP), MIN_PAIR_GAP)
    apart = list(range(dim)) if stack else [d for d in range(dim) if d != 1]
    for n in range(count, 0, -1):
        for _ in range(PLACEMENT_ATTEMPTS):
            balls = []
            for _ in range(n):
                r = max(rng.uniform(*RADIUS_RANGE), MIN_RADIUS_CELLS * h_coarse)
                margin = r + wall_gap
                if any(2 * margin >= e for e in extent):
                    break
                c = [rng.uniform(0.0, e) if p else rng.uniform(margin, e - margin)
                     for e, p in zip(extent, periodic)]
                if all(separation(c, b[0], extent, periodic, apart) > r + b[1] + pair_gap
                       for b in balls):
                    balls.append((c, r))
            if len(balls) == n:
                return balls
    raise RuntimeError("no room for a single ball; widen the box or shrink RADIUS_RANGE")


def close_pair(rng, dim, extent, periodic, h_fine, balls):
    """Move the second ball to a gap of CLOSE_PAIR_GAP_CELLS finest cells from the first
    (the contact range is one finest cell), in a random direction where it stays clear of
    the walls and of the other balls; balls is changed in place. Whether it found room."""
    wall_gap = min(WALL_GAP_CELLS * h_fine, MAX_GAP)
    pair_gap = max(min(PAIR_GAP_CELLS * h_fine, MAX_GAP), MIN_PAIR_GAP)
    (c0, r0), (_, r1) = balls[0], balls[1]
    for _ in range(PLACEMENT_ATTEMPTS):
        e = [rng.gauss(0, 1) for _ in range(dim)]
        norm = math.hypot(*e)
        distance = r0 + r1 + rng.uniform(*CLOSE_PAIR_GAP_CELLS) * h_fine
        c = [c0[d] + distance * e[d] / norm for d in range(dim)]
        c = [c[d] % extent[d] if periodic[d] else c[d] for d in range(dim)]
        if any(not periodic[d] and not r1 + wall_gap <= c[d] <= extent[d] - r1 - wall_gap
               for d in range(dim)):
            continue
        if all(separation(c, b, extent, periodic, range(dim)) > r1 + rb + pair_gap
               for b, rb in balls[2:]):
            balls[1] = (c, r1)
            return True
    return False


def make_scene(seed, index, dim, steps_range, level_range):
    """A random valid scene as (prm text, one-line summary)."""
    rng = random.Random(f"{seed}:{index}")
    extent, subdivisions, global_refinements, levels, h_coarse, h_fine = \
        choose_mesh(rng, dim, level_range)
    # Gravity is along -y: y is never periodic, the lateral directions may be.
    periodic = [False] * dim
    for d in [0] + ([2] if dim == 3 else []):
        periodic[d] = rng.random() < PERIODIC_CHANCE
    dt = rng.choice(TIME_STEPS)
    steps = rng.randint(*steps_range)
    # An adapted mesh may get longer steps below: stack balls only if even those keep the
    # run short.
    longest = steps * (max(TIME_STEPS) if levels > 0 else dt)
    balls = place_particles(rng, dim, extent, periodic, h_coarse, h_fine, rng.randint(1, 3),
                            stack=longest <= SHORT_RUN)
    # Contacts come from a stream of their own, so the rest of a scene does not depend on
    # them: the model, lubrication, and a pair placed within the contact range.
    contacts_rng = random.Random(f"{seed}:{index}:contacts")
    model = contacts_rng.choice(CONTACT_MODELS)
    lubrication = contacts_rng.random() < LUBRICATION_CHANCE
    close = (model != "none" and len(balls) > 1
             and contacts_rng.random() < CLOSE_PAIR_CHANCE
             and close_pair(contacts_rng, dim, extent, periodic, h_fine, balls))

    densities, motions, directions = [], [], []
    drive = 0.0  # largest |rho_P - rho_f| R^2 of a free ball
    for c, r in balls:
        densities.append(rng.uniform(*rng.choice(DENSITY_RANGES)))
        roll = rng.random()
        motions.append("fixed" if roll < FIXED_CHANCE else
                       "prescribed" if roll < FIXED_CHANCE + PRESCRIBED_CHANCE else "free")
        # Velocity (of unit size per component) and angular velocity of a prescribed ball.
        directions.append(([rng.uniform(-1, 1) for _ in range(dim)],
                           [rng.uniform(-1, 1) for _ in range(1 if dim == 2 else 3)]))
        if motions[-1] == "free":
            drive = max(drive, abs(densities[-1] - 1.0) * r * r)

    convection = rng.random() < CONVECTION_CHANCE
    cut_rule = rng.choice(["gauss", "level set"])
    scheme = rng.choice(["BDF1", "BDF2"])
    solver = "Amesos_Klu" if rng.random() < KLU_CHANCE else "Amesos_Mumps"
    if dim == 3 and 1.0 / h_fine > KLU_MAX_FINEST_CELLS_3D:
        solver = "Amesos_Mumps"
    ordering = rng.choice(["metis", "auto"])
    gravity = [0.0] * dim
    gravity[1] = -rng.uniform(*GRAVITY_RANGE)
    highest = VISCOSITY_RANGE[1]
    if levels > 0 and drive > 0:
        def moving(step):  # the viscosity at which the ball crosses TRAVEL_CELLS cells
            travel = SETTLING_FACTOR * drive * abs(gravity[1]) * steps * step
            return travel / (TRAVEL_CELLS * h_fine)
        # Too short a run even at the lowest viscosity: longer steps.
        longer = [t for t in TIME_STEPS if t >= dt and moving(t) >= VISCOSITY_RANGE[0]]
        dt = longer[0] if longer else max(TIME_STEPS)
        highest = max(min(highest, moving(dt)), VISCOSITY_RANGE[0])
    viscosity = math.exp(rng.uniform(math.log(VISCOSITY_RANGE[0]), math.log(highest)))
    end_time = steps * dt

    entries = []
    for (c, r), density, motion, (v, w) in zip(balls, densities, motions, directions):
        entry = f"{vec(c)} : {fmt(r)} : {fmt(density)}"
        if motion == "fixed":
            entry += " : fixed"
        elif motion == "prescribed":
            speed = PRESCRIBED_TRAVEL_CELLS * h_fine / end_time
            entry += f" : prescribed : {vec([speed * x for x in v])} : {vec(w)}"
        entries.append(entry)
    walls = []
    # A sliding lid breaks the symmetry of the box; only along a wall-bounded direction,
    # or it would carry the balls across a periodic boundary.
    sliding = [d for d in range(dim) if d != 1 and not periodic[d]]
    if sliding and rng.random() < LID_CHANCE:
        lid = [0.0] * dim
        lid[rng.choice(sliding)] = rng.uniform(-LID_SPEED_MAX, LID_SPEED_MAX)
        walls.append(f"y+: {vec(lid)}")

    summary = (f"{dim}D {'x'.join(map(str, subdivisions))}+{global_refinements}g "
               f"levels {levels}, {len(balls)} ball(s) {'/'.join(motions)}, "
               f"{'Navier-Stokes' if convection else 'Stokes'}, "
               f"periodic {''.join(a for a, p in zip(AXES, periodic) if p) or '-'}, "
               f"{cut_rule}, {solver[len('Amesos_'):]}{', lid' if walls else ''}, "
               f"dt {fmt(dt)} x {steps}")
    body = f"""set Dimension = {dim}
set Gravity = {vec(gravity)}
subsection Geometry
  set Lower corner = {vec([0.0] * dim)}
  set Upper corner = {vec(extent)}
  set Subdivisions = {', '.join(map(str, subdivisions))}
  set Global refinements = {global_refinements}
  set Periodic directions = {', '.join(a for a, p in zip(AXES, periodic) if p)}
end
subsection Boundary conditions
  set Wall velocities = {'; '.join(walls)}
end
subsection Fluid
  set Density = 1
  set Viscosity = {fmt(viscosity)}
  set Convection = {'true' if convection else 'false'}
end
subsection Particles
  set Particles = {'; '.join(entries)}
  set Angular velocity closure = {rng.choice(['torque balance', 'kinematic'])}
end
subsection Refinement
  set Particle refinement levels = {levels}
  set Refinement interval = {rng.choice([1, 1, 2])}
end
subsection Quadrature
  set Cut cells = {cut_rule}
  set Gauss points in cut cells = {rng.choice(GAUSS_POINTS)}
  set Level set order = {rng.choice(LEVEL_SET_ORDERS[dim])}
end
subsection Initial conditions
  set Pressure = {rng.choice(['zero', 'hydrostatic'])}
end
subsection Solver
  set Direct solver = {solver}
  set MUMPS ordering = {ordering}
  set Reuse Jacobian = {rng.choice(['true', 'false'])}
end
subsection Time
  set Time step = {fmt(dt)}
  set End time = {end_time:.10g}
  set Scheme = {scheme}
end
subsection Output
  set Directory = output
  set VTU interval = 0
end
"""
    body += f"subsection Collisions\n  set Model = {model}\n"
    if (model == "spring-dashpot" and "closure = torque balance" in body
            and contacts_rng.random() < FRICTION_CHANCE):
        body += f"  set Friction coefficient = {fmt(contacts_rng.uniform(*FRICTION_RANGE))}\n"
        model += " with friction"
    body += "end\n"
    if lubrication:
        body += "subsection Lubrication\n  set Enabled = true\nend\n"
        model += ", lubrication"
    summary += f", contacts {model}{', a pair in contact' if close else ''}"
    return f"# Parallel-consistency scene {index} of seed {seed}: {summary}\n" + body, summary


# ------------------------------------------------------------------------------ prm facts
def scene_scales(text):
    """(box size, smallest radius) for the comparison scales."""
    e = prm_entries(text)
    lower = [float(v) for v in e.get("Geometry/Lower corner", "-0.5, -0.5, -0.5").split(",")]
    upper = [float(v) for v in e.get("Geometry/Upper corner", "0.5, 1.5, 0.5").split(",")]
    radii = [float(p.split(":")[1])
             for p in e.get("Particles/Particles", "").split(";") if p.strip()]
    box = max(u - l for l, u in zip(lower, upper))
    return box, min(radii, default=box)


# ------------------------------------------------------------------------------ running
def end_group(process):
    """End a run started in a process group of its own: mpirun and all its ranks."""
    try:
        os.killpg(process.pid, signal.SIGTERM)
        try:
            process.wait(timeout=KILL_GRACE)
        except subprocess.TimeoutExpired:
            os.killpg(process.pid, signal.SIGKILL)
    except ProcessLookupError:
        pass  # already gone
    process.wait()


def last_step(log):
    """', after step N (t = T)' from the last step line of a run's output, or ''."""
    with open(log, errors="replace") as f:
        steps = [l.split() for l in f if l.startswith("step")]
    # A step line reads 'step N  t = T / END ...'.
    if not steps or len(steps[-1]) < 5:
        return ""
    return f", after step {steps[-1][1]} (t = {steps[-1][4]})"


def longest_step(log):
    """Wall seconds of the slowest step in a run's output (0 if none)."""
    with open(log, errors="replace") as f:
        times = [float(m.group(1)) for m in map(STEP_SECONDS.search, f) if m]
    return max(times, default=0.0)


def watch(process, log, started, timeout, stall):
    """(exit status, None) once the run ends; (None, why) when it hangs (then killed)."""
    size, last_output = 0, started
    while process.poll() is None:
        time.sleep(POLL_SECONDS)
        now = time.time()
        if os.path.getsize(log) != size:
            size, last_output = os.path.getsize(log), now
        stalled = now - last_output > stall
        if stalled or now - started > timeout:
            end_group(process)
            why = f"no output for {stall:.0f} s" if stalled else f"not done in {timeout:g} s"
            return None, f"{why}{last_step(log)} (killed)"
    return process.returncode, None


def run_fdparticle(executable, prm, ranks, cwd, timeout, stall):
    """(status, message, seconds): status 'ok', 'error' (a clean fdparticle error), 'crash'
    or 'hang'. The run's output goes to CWD/ranks-N.log."""
    # Several ranks through scripts/mpirun.sh: the rank counts are oversubscribed on small
    # machines, so the ranks are not pinned to cores and idle ranks yield theirs.
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    cmd = [executable, prm]
    if ranks > 1:
        cmd = ["bash", os.path.join(TOP, "scripts", "mpirun.sh"), str(ranks)] + cmd
    log = os.path.join(cwd, f"ranks-{ranks}.log")
    started = time.time()
    with open(log, "w") as out, open(log + ".stderr", "w+") as err:
        # A process group of its own: a hung run is ended with all its ranks, not only mpirun.
        process = subprocess.Popen(cmd, cwd=cwd, env=env, stdout=out, stderr=err,
                                   start_new_session=True)
        try:
            returncode, hung = watch(process, log, started, timeout, stall)
        except BaseException:
            # Interrupted: take the ranks along.
            end_group(process)
            raise
        seconds = time.time() - started
        err.seek(0)
        stderr = err.read()
    os.remove(log + ".stderr")
    with open(log, "a") as out:
        out.write(stderr)
    if hung:
        return "hang", hung, seconds
    if returncode == 0:
        return "ok", "", seconds
    lines = stderr.splitlines()
    errors = [l for l in lines if l.startswith("fdparticle: error")]
    if errors:
        # One rank's error in parallel reads 'error on rank R: ...': keep the message.
        if errors[0].startswith("fdparticle: error on rank"):
            message = errors[0].split(": ", 2)[-1]
        else:
            message = errors[0][len("fdparticle: error: "):]
        return "error", message, seconds
    # The C library's or MPI's word on the signal, not mpirun's banner lines.
    telling = [l for l in lines if CRASH_LINE.search(l)] or \
        [l for l in lines if l.strip("- ")][-1:] or ["(no message)"]
    status = f"exit status {returncode}"
    # Shells and mpirun report a rank killed by signal S as 128 + S.
    number = -returncode if returncode < 0 else returncode - 128
    if number in set(signal.Signals):
        status += f" ({signal.Signals(number).name})"
    return "crash", f"{status}{last_step(log)}: {telling[0].strip()[:200]}", seconds


def read_table(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    if not rows:
        raise ValueError(f"{os.path.basename(path)} is empty")
    return rows[0], rows[1:]


def number(text):
    """The value of a CSV cell; NaN for what is no number (reported by non_finite)."""
    try:
        return float(text)
    except ValueError:
        return math.nan


def non_finite(path):
    """Descriptions of NaN/inf or unreadable numbers in a CSV file."""
    header, rows = read_table(path)
    found = []
    for i, row in enumerate(rows):
        for name, value in zip(header, row):
            if name in IGNORED_COLUMNS:
                continue
            try:
                ok = math.isfinite(float(value))
            except ValueError:
                ok = False
            if not ok:
                found.append(f"{os.path.basename(path)} row {i + 1} column {name}: {value!r}")
    return found


def step_numbers(out_dir):
    """{time: step} from OUT_DIR/statistics.csv, with step 0 at t = 0."""
    header, rows = read_table(os.path.join(out_dir, "statistics.csv"))
    steps = {0.0: 0}
    if "step" in header and "time" in header:
        for row in rows:
            steps[number(row[header.index("time")])] = row[header.index("step")]
    return steps


def compare_particles(ref_dir, other_dir, box, radius):
    """(row count mismatch, value mismatches in row order, largest normalised difference,
    where) over the rows both files have."""
    header, rows = read_table(os.path.join(ref_dir, "particles.csv"))
    header_o, rows_o = read_table(os.path.join(other_dir, "particles.csv"))
    if header != header_o:
        return [f"particles.csv headers differ: {header} vs {header_o}"], [], math.inf, "header"
    row_count = []
    if len(rows) != len(rows_o):
        row_count.append(f"particles.csv has {len(rows_o)} rows, {len(rows)} on the reference")
    problems = []
    rows, rows_o = rows[:len(rows_o)], rows_o[:len(rows)]
    columns = [(i, h) for i, h in enumerate(header) if h not in IGNORED_COLUMNS]
    scale = column_scales(header, [rows, rows_o], box, radius)
    worst, where = 0.0, ""
    steps = step_numbers(ref_dir)
    for row, row_o in zip(rows, rows_o):
        when = dict(zip(header, row))
        place = f"t = {when.get('time', '?')}"
        if number(when.get("time", "")) in steps:
            place = f"step {steps[number(when['time'])]} ({place})"
        for i, h in columns:
            a, b = number(row[i]), number(row_o[i])
            tol = TIME_REL_TOL if h in ("time", "id") else REL_TOL
            # The difference in units of REL_TOL's allowance (testlib's rule).
            allowed = allowed_difference(a, b, 1.0, FLOOR_FRACTION, scale[h])
            diff = abs(a - b) / allowed if allowed > 0 else 0.0
            if h not in ("time", "id") and diff > worst:
                worst, where = diff, f"column {h}, {place}"
            if not diff <= tol:
                problems.append(f"{place}, particle {when.get('id', '?')}, column {h}: {b!r} vs "
                                f"{a!r} on the reference (relative difference {diff:.2g})")
    return row_count, problems, worst, where


def compare_statistics(ref_dir, other_dir):
    """The step sequence and the mesh sizes must be the same on every rank count."""
    header, rows = read_table(os.path.join(ref_dir, "statistics.csv"))
    header_o, rows_o = read_table(os.path.join(other_dir, "statistics.csv"))
    problems = []
    if len(rows) != len(rows_o):
        problems.append(f"statistics.csv has {len(rows_o)} steps, {len(rows)} on the reference")
    for name in MESH_COLUMNS:
        if name not in header or name not in header_o:
            continue
        i, j = header.index(name), header_o.index(name)
        for r, (row, row_o) in enumerate(zip(rows, rows_o)):
            a, b = number(row[i]), number(row_o[j])
            if abs(a - b) > TIME_REL_TOL * max(abs(a), abs(b)):
                problems.append(f"statistics.csv step {row[0]} column {name}: "
                                f"{row_o[j]} vs {row[i]}")
                break
    return problems


def check_scene(executable, prm_text, scene_dir, ranks_list, timeout):
    """(failure descriptions, largest normalised difference, where) for one scene."""
    os.makedirs(scene_dir, exist_ok=True)
    outcomes = {}
    for ranks in ranks_list:
        out_dir = os.path.join(scene_dir, f"ranks-{ranks}")
        shutil.rmtree(out_dir, ignore_errors=True)
        prm = os.path.join(scene_dir, f"ranks-{ranks}.prm")
        with open(prm, "w") as f:
            # A later 'set' overrides an earlier one: each rank count has its own output.
            f.write(prm_text + f"\nsubsection Output\n  set Directory = {out_dir}\nend\n")
        stall = STALL_SECONDS
        if outcomes:
            first = os.path.join(scene_dir, f"ranks-{ranks_list[0]}.log")
            stall = max(stall, STALL_FACTOR * longest_step(first))
        outcomes[ranks] = run_fdparticle(executable, prm, ranks, scene_dir, timeout, stall)

    failures = []
    reference = ranks_list[0]
    statuses = {outcome[:2] for outcome in outcomes.values()}
    if len(statuses) == 1 and next(iter(statuses))[0] == "error":
        return [f"invalid scene: every rank count stops with: {outcomes[reference][1]}"], 0.0, ""
    for ranks, (status, message, _) in outcomes.items():
        if status != "ok":
            failures.append(f"{ranks} rank(s): {status}: {message}")
    written = []
    for ranks in ranks_list:
        paths = [os.path.join(scene_dir, f"ranks-{ranks}", name)
                 for name in ("particles.csv", "statistics.csv")]
        if outcomes[ranks][0] == "ok":
            failures += [f"{ranks} rank(s): {os.path.basename(p)} was not written"
                         for p in paths if not os.path.exists(p)]
        if all(os.path.exists(p) for p in paths):
            written.append(ranks)
            for p in paths:
                failures += [f"{ranks} rank(s): non-finite {x}" for x in non_finite(p)[:5]]
    if reference not in written:
        return failures, 0.0, ""

    box, radius = scene_scales(prm_text)
    worst, where = 0.0, ""
    ref_dir = os.path.join(scene_dir, f"ranks-{reference}")
    for ranks in written[1:]:
        other = os.path.join(scene_dir, f"ranks-{ranks}")
        rows, problems, diff, at = compare_particles(ref_dir, other, box, radius)
        complete = outcomes[ranks][0] == "ok" and outcomes[reference][0] == "ok"
        if complete:
            problems = rows + problems + compare_statistics(ref_dir, other)
            if diff > worst:
                worst, where = diff, f"{ranks} vs {reference} ranks, {at}"
        pair = f"{ranks} vs {reference} rank(s)" + ("" if complete else ", the rows both wrote")
        if problems:
            failures.append(f"{pair}: {len(problems)} mismatch(es), first: {problems[0]}")
        elif not complete:
            failures.append(f"{pair}: agree (largest relative difference {diff:.1e})")
    return failures, worst, where


# ------------------------------------------------------------------------------ main
def int_list(text):
    return [int(x) for x in text.split(",") if x.strip()]


def int_range(lowest):
    def parse(text):
        values = int_list(text)
        if len(values) == 1:
            values *= 2
        if len(values) != 2 or not lowest <= values[0] <= values[1]:
            raise argparse.ArgumentTypeError(f"'{text}' is not MIN,MAX with {lowest} <= MIN <= MAX")
        return tuple(values)
    return parse


def main():
    parser = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0],
        formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--seed", type=int, default=None,
                        help="scene generator seed (default: from the clock, printed)")
    parser.add_argument("--scenes", type=int, default=10, help="number of random scenes")
    parser.add_argument("--ranks", type=int_list, default=[1, 2, 3],
                        help="rank counts, compared with the first (default 1,2,3)")
    parser.add_argument("--dims", type=int_list, default=[2, 2, 3],
                        help="dimensions of the scenes, cycled in order (default 2,2,3: "
                             "two 2D scenes for each 3D one)")
    parser.add_argument("--steps", type=int_range(1), default=(10, 40),
                        help="MIN,MAX time steps of a 2D scene (default 10,40)")
    parser.add_argument("--steps-3d", type=int_range(1), default=(2, 8),
                        help="MIN,MAX time steps of a 3D scene (default 2,8)")
    parser.add_argument("--levels", type=int_range(0), default=(0, 2),
                        help="MIN,MAX Particle refinement levels (default 0,2; the cost cap "
                             "of fine meshes may lower MAX)")
    parser.add_argument("--executable", default=os.path.join(TOP, "build", "fdparticle"))
    parser.add_argument("--work",
                        default=os.path.join(TOP, "benchmarks", "work", "parallel_consistency"),
                        help="scene directories WORK/scene-K go here (those of an earlier "
                             "check are removed first)")
    parser.add_argument("--keep", action="store_true",
                        help="keep the directories of passing scenes too (failing ones are "
                             "always kept)")
    parser.add_argument("--timeout", type=float, default=900.0,
                        help=f"seconds one run may take in all before it counts as hung "
                             f"(default 900; also after {STALL_SECONDS:g} s without output)")
    parser.add_argument("--budget", type=float, default=None,
                        help="start no new scene after this many seconds (--scenes is then "
                             "a maximum)")
    parser.add_argument("--prm", default=None,
                        help="check this prm file instead of random scenes (to reproduce a "
                             "failure)")
    opts = parser.parse_args()
    if opts.seed is None:
        opts.seed = int(time.time()) % 1000000
    if any(d not in (2, 3) for d in opts.dims) or not opts.dims:
        parser.error("--dims takes 2 and/or 3")
    if not opts.ranks or any(r < 1 for r in opts.ranks):
        parser.error("--ranks takes positive integers")
    executable = os.path.abspath(opts.executable)
    if not os.access(executable, os.X_OK):
        parser.error(f"no executable {executable}; build first or pass --executable")

    if opts.prm:
        # Read before WORK is cleaned: the prm of a failed scene lies in WORK.
        with open(opts.prm) as f:
            scenes = [(f.read(), os.path.basename(opts.prm))]
    work = os.path.abspath(opts.work)
    created = not os.path.isdir(work)
    os.makedirs(work, exist_ok=True)
    # Only what an earlier check left: WORK may hold other files.
    for name in os.listdir(work):
        if name.startswith("scene-"):
            shutil.rmtree(os.path.join(work, name))
    here = os.path.relpath(os.path.abspath(__file__))
    if opts.prm:
        print(f"parallel consistency of {opts.prm} on ranks {','.join(map(str, opts.ranks))}")
    else:
        scenes = None
        print(f"parallel consistency: seed {opts.seed}, {opts.scenes} scenes, "
              f"ranks {','.join(map(str, opts.ranks))}, work {work}")
    sys.stdout.flush()

    started = time.time()
    passed, failed = 0, []
    worst, worst_where = 0.0, ""
    count = len(scenes) if scenes else opts.scenes
    for index in range(count):
        if opts.budget is not None and index > 0 and time.time() - started > opts.budget:
            print(f"time budget of {opts.budget:g} s used: stopping after {index} scenes")
            break
        if scenes:
            text, summary = scenes[index]
        else:
            dim = opts.dims[index % len(opts.dims)]
            steps = opts.steps if dim == 2 else opts.steps_3d
            text, summary = make_scene(opts.seed, index, dim, steps, opts.levels)
        scene_dir = os.path.join(work, f"scene-{index}")
        os.makedirs(scene_dir)
        with open(os.path.join(scene_dir, "scene.prm"), "w") as f:
            f.write(text)
        t0 = time.time()
        failures, diff, where = check_scene(executable, text, scene_dir, opts.ranks, opts.timeout)
        seconds = time.time() - t0
        if failures:
            failed.append(index)
            print(f"scene {index} ({summary}): FAIL ({seconds:.1f} s)")
            for failure in failures[:10]:
                print(f"    {failure}")
            prm = os.path.join(scene_dir, "scene.prm")
            print(f"    reproduce: /usr/bin/python3 {here} --prm {prm} "
                  f"--ranks {','.join(map(str, opts.ranks))} --executable {executable} "
                  f"--work {os.path.join(work, 'reproduce')}")
        else:
            passed += 1
            if diff > worst:
                worst, worst_where = diff, f"scene {index}, {where}"
            print(f"scene {index} ({summary}): pass, max relative difference {diff:.1e} "
                  f"({seconds:.1f} s)")
            if not opts.keep:
                shutil.rmtree(scene_dir)
        sys.stdout.flush()
    if created and not os.listdir(work):
        os.rmdir(work)
    print(f"largest relative difference between rank counts in passing scenes: {worst:.2e}"
          + (f" ({worst_where})" if worst_where else "")
          + f"; tolerance {REL_TOL:g}; {time.time() - started:.0f} s")
    print(f"{passed} passed, {len(failed)} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
