#!/usr/bin/python3
"""Parameter fuzzing: bad input must never crash fdparticle.

Starts from every shipped scene (prm/*.prm, prm/validation/*.prm, tests/*.prm; not the
tests whose '# test-args:' run something other than the scene itself), shortens each to a
few time steps, and runs mutants of it: an entry deleted, duplicated, garbled (random
characters, truncated), set to an extreme value (0, -1, +-1e308, nan, inf, empty, huge
integers), vectors of the wrong length, overlapping particles, particles outside the box,
absurd refinement, zero or negative time steps, absurd step counts, a wrong Dimension,
broken file structure. Each mutant runs on 1 rank (a fraction on --ranks ranks) under a
time limit and an address-space limit. It is OK if

  (a) it exits 0 and its output directory holds CSV files that are complete (a header,
      rows as long as the header, a final newline) and free of nan/inf, or
  (b) it exits non-zero with exactly one 'fdparticle: error' line on stderr, nothing
      else on stderr, no MPI abort report, stack trace or deal.II exception box, and
      either no output directory (an error before the first output) or one whose CSV
      files are complete as in (a) (an error during the run).

Everything else fails: a signal, a time-out (hang), an abort report, an out-of-memory
error (the program should have refused the input before allocating), nan/inf in the
output, a missing, repeated or garbled error line, a half-written output directory, a
run that replaced its own parameter file. Open MPI's mpirun reports every non-zero exit
of a rank in a framed notice ("Primary job terminated normally, but 1 process returned a
non-zero exit code"), also after a clean error on every rank; that exact notice is
removed before the checks, while MPI_Abort's report ("MPI_ABORT was invoked") fails.
Failing mutants are copied to WORK/failures/ with the command and what went wrong.

Runs are kept short: End time is cut to --steps steps (of the scene's Time step and of the
default one, for mutants that delete it), Newton to 8 iterations and recovery to 2
halvings; a run on N ranks gets N times the larger of --timeout and 20 times its unchanged
scene's run (timed at the start, so a busy machine gives more time). Each process may map
--memory GiB.

    benchmarks/fuzz_parameters.py --seed 1 --count 200
    benchmarks/fuzz_parameters.py --duration 2400 --count 0       # as many as fit in 40 min
"""
import argparse
import glob
import os
import random
import re
import resource
import shutil
import signal
import subprocess
import sys
import time

TOP = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TESTS = os.path.join(TOP, "tests")
MPIRUN = os.path.join(TOP, "scripts", "mpirun.sh")
# A mutant's run is a hang when it takes more than this many times its unchanged scene's
# run (and more than --timeout).
HANG_FACTOR = 20
SCENE_GLOBS = ("prm/*.prm", "prm/validation/*.prm", "tests/*.prm")

# The output directory set in every base scene, relative to the mutant's own directory, so
# that a run writes only there (fixtures that scenes refer to are copied in too).
OUTPUT_NAME = "out"

# Caps of the failure path of a step (the program's defaults are 20 and 6): a diverging
# Newton solve then gives up after 3 x 8 iterations instead of 7 x 20.
MAX_NEWTON = 8
MAX_REDUCTIONS = 2
# Extreme values for any entry; the integers overflow int, unsigned int and int64.
EXTREME_VALUES = ["0", "-1", "1e308", "-1e308", "nan", "inf", "-inf", "", "2147483648",
                  "4294967296", "9223372036854775808", "1000000000000000000000000000000",
                  "1e-308", "5e-324", "-0", "1e999", "0x10", "1,5"]
# Refinement that no mesh can afford (12: the largest Global refinements the pattern
# accepts; even a single base cell gives 4^12 = 1.7e7 cells in 2D), or out of range. Values
# between what runs in seconds and the program's cell limit are valid, only expensive
# requests: they are not generated, a time-out would tell nothing.
ABSURD_REFINEMENTS = ["12", "30", "-1", "1e9", "2.5", "9"]
ABSURD_SUBDIVISIONS = ["0", "-3", "1e7", "4294967297", "1e308", "8.5", "nan", "100000"]
ABSURD_TIME_STEPS = ["0", "-0.1", "1e-300", "5e-324", "1e308", "nan", "inf"]
ABSURD_END_TIMES = ["-1", "0", "1e308", "inf", "1e300", "nan", "1e12"]
# No digits and no 'e': a garbled number must not become a valid, merely larger one
# ("16" -> "1e6" subdivisions is a valid request for an expensive run).
JUNK_CHARACTERS = "abcxyzQ!$%&*()[]{}<>?|~^`'\"=;:,.+-#\\ \t"
VECTOR_ENTRIES = {"Gravity", "Lower corner", "Upper corner", "Subdivisions", "Body force"}
DIRECTORY_ENTRIES = {("Output", "Directory"), ("Checkpointing", "Directory")}


# ---------------------------------------------------------------------------------------
# Scenes
# ---------------------------------------------------------------------------------------
class Scene:
    """The lines of a parameter file and its 'set' entries (subsection path, name)."""

    def __init__(self, lines):
        self.lines = list(lines)

    def entries(self):
        """[(line index, path tuple, name, value)] in file order."""
        found, path = [], []
        for i, raw in enumerate(self.lines):
            # Any white space separates the keywords, as in ParameterHandler.
            line = raw.split("#")[0].strip()
            words = line.split(None, 1)
            if len(words) == 2 and words[0] == "subsection":
                path.append(words[1].strip())
            elif line == "end":
                if path:
                    path.pop()
            elif len(words) == 2 and words[0] == "set" and "=" in words[1]:
                name, value = words[1].split("=", 1)
                found.append((i, tuple(path), " ".join(name.split()), value.strip()))
        return found

    def value(self, path, name, default=None):
        """The value in force: the last 'set' of the entry wins, as in ParameterHandler."""
        value = default
        for _, p, n, v in self.entries():
            if p == tuple(path) and n == name:
                value = v
        return value

    def set(self, path, name, value):
        """Replace every 'set' of the entry, or append one."""
        hits = [e for e in self.entries() if e[1] == tuple(path) and e[2] == name]
        for i, *_ in hits:
            indent = self.lines[i][:len(self.lines[i]) - len(self.lines[i].lstrip())]
            self.lines[i] = f"{indent}set {name} = {value}"
        if not hits:
            self.append(path, name, value)

    def append(self, path, name, value):
        self.lines += [f"subsection {p}" for p in path] + [f"set {name} = {value}"]
        self.lines += ["end"] * len(path)

    def text(self):
        return "\n".join(self.lines) + "\n"


def read_scene(path, seen=()):
    """The lines of a scene with 'include FILE' lines replaced by the file's lines."""
    lines = []
    with open(path, encoding="utf-8", errors="replace") as f:
        for raw in f.read().splitlines():
            stripped = raw.split("#")[0].strip()
            if stripped.startswith("include "):
                name = stripped[len("include "):].strip()
                candidates = [name, os.path.join(os.path.dirname(path), name)]
                target = next((c for c in candidates if os.path.isfile(c)), None)
                if target and os.path.abspath(target) not in seen:
                    lines += read_scene(target, seen + (os.path.abspath(path),))
                    continue
            lines.append(raw)
    return lines


def shipped_scenes(patterns):
    """{name: (path, lines)} of the plain scenes matching the globs (relative to the top)."""
    scenes = {}
    for pattern in patterns:
        for path in sorted(glob.glob(os.path.join(TOP, pattern))):
            lines = read_scene(path)
            if any(re.match(r"^#\s*test-args:", l) for l in lines):
                continue  # runs something else than 'fdparticle SCENE'
            scenes[os.path.relpath(path, TOP)] = lines
    return scenes


def declared_parameters(executable):
    """[(path, name, default)] of every entry the program declares."""
    listing = subprocess.run([executable, "--print-parameters"], capture_output=True,
                             text=True, check=True).stdout
    return [(p, n, v) for _, p, n, v in Scene(listing.splitlines()).entries()]


def to_float(text, fallback):
    try:
        return float(text)
    except (TypeError, ValueError):
        return fallback


def capped(lines, steps, defaults):
    """The scene shortened to at most 'steps' time steps, its output in OUTPUT_NAME."""
    scene = Scene(lines)
    # Also with the default step: a mutant that deletes 'Time step' gets that one.
    default_dt = to_float(defaults.get((("Time",), "Time step")), 0.1)
    dt = to_float(scene.value(("Time",), "Time step", str(default_dt)), None)
    end = to_float(scene.value(("Time",), "End time", "1"), None)
    if dt and end is not None and dt > 0 and end > steps * min(dt, default_dt):
        scene.set(("Time",), "End time", repr(steps * min(dt, default_dt)))
    # A failing Newton solve is retried with halved steps: bound that chain too.
    for path, name, cap in ((("Solver",), "Max nonlinear iterations", MAX_NEWTON),
                            (("Time",), "Max time step reductions", MAX_REDUCTIONS)):
        value = to_float(scene.value(path, name, None), None)
        if value is None or value > cap:
            scene.set(path, name, str(cap))
    scene.set(("Output",), "Directory", OUTPUT_NAME)
    # Fields every step would be most of the run time of a mutant; every other step
    # still exercises the writer.
    if to_float(scene.value(("Output",), "VTU interval", "1"), 0) == 1:
        scene.set(("Output",), "VTU interval", "2")
    return scene


# ---------------------------------------------------------------------------------------
# Mutations: each changes the scene and returns a description.
# ---------------------------------------------------------------------------------------
def dimension_of(scene):
    return 2 if scene.value((), "Dimension", "3").strip() == "2" else 3


def safe_directory(text):
    """A garbled directory name that stays below the mutant's directory."""
    text = text.replace("..", "__").lstrip("/~ \t")
    return text


def garble(rng, value):
    kind = rng.choice(["random", "truncate", "insert", "replace", "append", "double"])
    if kind == "random" or not value:
        return "".join(rng.choice(JUNK_CHARACTERS) for _ in range(rng.randint(1, 12)))
    pos = rng.randrange(len(value) + 1)
    junk = rng.choice(JUNK_CHARACTERS)
    if kind == "truncate":
        return value[:rng.randrange(len(value))]
    if kind == "insert":
        return value[:pos] + junk + value[pos:]
    if kind == "replace":
        return value[:pos] + junk + value[pos + 1:]
    if kind == "append":
        return value + rng.choice([" x", ",", ";", ":", " 1", "e", "e5000", "..", " # c", "e-"])
    return value + value


def pick_entry(rng, scene):
    entries = scene.entries()
    return rng.choice(entries) if entries else None


def set_line(scene, entry, value):
    i, path, name, _ = entry
    if (path[-1] if path else "", name) in DIRECTORY_ENTRIES:
        value = safe_directory(value)
    indent = scene.lines[i][:len(scene.lines[i]) - len(scene.lines[i].lstrip())]
    scene.lines[i] = f"{indent}set {name} = {value}"
    return value


def entry_label(entry):
    return "/".join(entry[1] + (entry[2],))


def m_delete(rng, scene, ctx):
    e = pick_entry(rng, scene)
    if not e:
        return None
    del scene.lines[e[0]]
    return f"delete {entry_label(e)}"


def m_duplicate(rng, scene, ctx):
    e = pick_entry(rng, scene)
    if not e:
        return None
    scene.lines.insert(e[0] + 1, scene.lines[e[0]])
    if rng.random() < 0.5:
        v = set_line(scene, (e[0] + 1,) + e[1:], rng.choice(EXTREME_VALUES))
        return f"duplicate {entry_label(e)}, second = {v!r}"
    return f"duplicate {entry_label(e)}"


def m_garble(rng, scene, ctx):
    e = pick_entry(rng, scene)
    if not e:
        return None
    v = set_line(scene, e, garble(rng, e[3]))
    return f"garble {entry_label(e)} = {v!r}"


def m_extreme(rng, scene, ctx):
    value = rng.choice(EXTREME_VALUES)
    if rng.random() < 0.3:
        # An entry the scene leaves at its default.
        path, name, _ = rng.choice(ctx["declared"])
        if (path[-1] if path else "", name) in DIRECTORY_ENTRIES:
            value = safe_directory(value) or "x"
        scene.append(path, name, value)
        return f"add {'/'.join(path + (name,))} = {value!r}"
    e = pick_entry(rng, scene)
    if not e:
        return None
    v = set_line(scene, e, value)
    return f"extreme {entry_label(e)} = {v!r}"


def m_vector(rng, scene, ctx):
    entries = [e for e in scene.entries() if e[2] in VECTOR_ENTRIES]
    if not entries:
        return None
    e = rng.choice(entries)
    parts = [p.strip() for p in e[3].split(",")]
    kind = rng.choice(["drop", "add", "component"])
    if kind == "drop":
        parts = parts[:-1]
    elif kind == "add":
        parts.append(parts[-1] if parts else "1")
    else:
        parts[rng.randrange(len(parts))] = rng.choice(EXTREME_VALUES[:7] + ["1e-300"])
    v = set_line(scene, e, ", ".join(parts))
    return f"vector {entry_label(e)} = {v!r}"


def box(scene, dim):
    lo = [to_float(x, 0.0) for x in scene.value(("Geometry",), "Lower corner", "-0.5, -0.5, -0.5").split(",")]
    hi = [to_float(x, 1.0) for x in scene.value(("Geometry",), "Upper corner", "0.5, 1.5, 0.5").split(",")]
    lo, hi = (lo + [0.0] * 3)[:dim], (hi + [1.0] * 3)[:dim]
    return lo, hi


def fmt(xs):
    return ", ".join(f"{x:.6g}" for x in xs)


def m_particles(rng, scene, ctx):
    dim = dimension_of(scene)
    lo, hi = box(scene, dim)
    size = min(h - l for l, h in zip(lo, hi))
    mid = [(l + h) / 2 for l, h in zip(lo, hi)]
    current = scene.value(("Particles",), "Particles", "")
    entries = [x.strip() for x in current.split(";") if x.strip()]
    r = 0.1 * size
    kind = rng.choice(["overlap", "outside", "wall", "huge radius", "tiny radius", "many",
                       "motion", "fields", "same centre", "touching", "extreme field",
                       "prescribed extreme"])
    if kind == "overlap":
        entries += [f"{fmt(mid)} : {r} : 1.5", f"{fmt([mid[0] + r] + mid[1:])} : {r} : 1.5"]
    elif kind == "same centre" and entries:
        entries.append(entries[0])
    elif kind == "touching":
        entries = [f"{fmt(mid)} : {r} : 1.5", f"{fmt([mid[0] + 2 * r] + mid[1:])} : {r} : 1.5"]
    elif kind == "outside":
        entries.append(f"{fmt([h + size for h in hi])} : {r} : 2")
    elif kind == "wall":
        entries = [f"{fmt([lo[0] + r] + mid[1:])} : {r} : 2"]
    elif kind == "huge radius":
        entries = [f"{fmt(mid)} : {rng.choice(['1e308', str(10 * size), '1e30'])} : 2"]
    elif kind == "tiny radius":
        entries = [f"{fmt(mid)} : {rng.choice(['1e-12', '1e-300', '5e-324'])} : 2"]
    elif kind == "many":
        # Non-overlapping, away from the walls: a valid crowd on a small grid of sites.
        n = rng.randint(3, 8)
        rr = size / (4 * n)
        entries = [f"{fmt([lo[0] + (k + 0.5) * (hi[0] - lo[0]) / n] + mid[1:])} : {rr:.6g} : 1.5"
                   for k in range(n)]
    elif kind == "motion":
        entries = [f"{fmt(mid)} : {r} : 1.5 : " + rng.choice(
            ["prescribed", "frozen", "fixed : 1, 0", "prescribed : 1", "prescribed : " + fmt([1] * dim) + " : 1, 2, 3, 4",
             "free : x", "", "prescribed : " + fmt([0] * dim) + " : " + fmt([0] * (1 if dim == 2 else 3))])]
    elif kind == "fields":
        entries = [f"{fmt(mid)} : {r}" + rng.choice(["", " : 1.5 : free : 1 : 2 : 3 : 4", " ; ;", " : : ", " :: 1.5"])]
    elif kind == "extreme field":
        fields = [fmt(mid), str(r), "1.5"]
        fields[rng.randrange(3)] = rng.choice(EXTREME_VALUES)
        entries = [" : ".join(fields)]
    else:
        entries = [f"{fmt(mid)} : {r} : 1.5 : prescribed : " +
                   fmt([rng.choice([1e308, -1e308, 1e10, 0.0])] + [0.0] * (dim - 1))]
    value = "; ".join(entries)
    scene.set(("Particles",), "Particles", value)
    return f"particles ({kind}) = {value!r}"


def m_refinement(rng, scene, ctx):
    kind = rng.choice(["Global refinements", "Particle refinement levels", "Subdivisions",
                       "Band width", "Refinement interval"])
    if kind == "Subdivisions":
        dim = dimension_of(scene)
        current = scene.value(("Geometry",), "Subdivisions", "8, 16, 8").split(",")
        parts = ([p.strip() for p in current] + ["4"] * 3)[:dim]
        for d in rng.sample(range(dim), rng.randint(1, dim)):
            parts[d] = rng.choice(ABSURD_SUBDIVISIONS)
        value = ", ".join(parts)
        scene.set(("Geometry",), "Subdivisions", value)
    elif kind == "Global refinements":
        value = rng.choice(ABSURD_REFINEMENTS)
        scene.set(("Geometry",), kind, value)
    elif kind == "Particle refinement levels":
        value = rng.choice(ABSURD_REFINEMENTS + ["8"] if dimension_of(scene) == 2 else ABSURD_REFINEMENTS)
        scene.set(("Refinement",), kind, value)
    elif kind == "Band width":
        value = rng.choice(["0", "-1", "1e308", "nan", "1e-300"])
        scene.set(("Refinement",), kind, value)
    else:
        value = rng.choice(["0", "-1", "4294967296", "1e308"])
        scene.set(("Refinement",), kind, value)
    return f"refinement {kind} = {value!r}"


def m_time(rng, scene, ctx):
    kind = rng.choice(["Time step", "End time", "both", "Max time step reductions",
                       "Scheme", "Max nonlinear iterations", "Nonlinear tolerance"])
    if kind == "Time step":
        value = rng.choice(ABSURD_TIME_STEPS)
        scene.set(("Time",), "Time step", value)
    elif kind == "End time":
        value = rng.choice(ABSURD_END_TIMES)
        scene.set(("Time",), "End time", value)
    elif kind == "both":
        value = rng.choice(["1e308, 1e-308", "1e300, 1e-300", "1, 1e-17", "1e20, 1"])
        end, dt = value.split(", ")
        scene.set(("Time",), "End time", end)
        scene.set(("Time",), "Time step", dt)
    elif kind == "Max time step reductions":
        value = rng.choice(["-1", "51", "1e308", "50", "0", "nan"])
        scene.set(("Time",), kind, value)
    elif kind == "Scheme":
        value = rng.choice(["BDF3", "bdf2", "", "BDF2 BDF1", "BDF1;"])
        scene.set(("Time",), kind, value)
    elif kind == "Max nonlinear iterations":
        value = rng.choice(["0", "-1", "2147483648", "1e9"])
        scene.set(("Solver",), kind, value)
    else:
        value = rng.choice(["0", "-1", "nan", "1e308", "1e-308"])
        scene.set(("Solver",), kind, value)
    return f"time {kind} = {value!r}"


def m_dimension(rng, scene, ctx):
    value = rng.choice(["2", "3", "1", "4", "2.0", "", "three"])
    scene.set((), "Dimension", value)
    return f"Dimension = {value!r}"


def m_box(rng, scene, ctx):
    dim = dimension_of(scene)
    lo, hi = box(scene, dim)
    kind = rng.choice(["equal", "swapped", "tiny", "huge", "flat"])
    if kind == "equal":
        hi = list(lo)
    elif kind == "swapped":
        lo, hi = hi, lo
    elif kind == "tiny":
        hi = [l + 1e-300 for l in lo]
    elif kind == "huge":
        lo, hi = [-1e300] * dim, [1e300] * dim
    else:
        hi[-1] = lo[-1] + 1e-12
    scene.set(("Geometry",), "Lower corner", fmt(lo) if kind != "tiny" else ", ".join(repr(x) for x in lo))
    scene.set(("Geometry",), "Upper corner", ", ".join(repr(x) for x in hi))
    return f"box ({kind}) {fmt(lo)} .. {', '.join(repr(x) for x in hi)}"


def m_walls(rng, scene, ctx):
    dim = dimension_of(scene)
    zero = [0.0] * dim
    kind = rng.choice(["normal", "unknown face", "periodic face", "extreme", "garbled",
                       "double", "periodic all", "periodic junk"])
    if kind == "normal":
        v = list(zero)
        v[1] = 1.0
        value, entry = f"y+: {fmt(v)}", "Wall velocities"
    elif kind == "unknown face":
        value, entry = f"w+: {fmt(zero)}", "Wall velocities"
    elif kind == "periodic face":
        scene.set(("Geometry",), "Periodic directions", "x")
        value, entry = f"x-: {fmt([0.0, 1.0] + [0.0] * (dim - 2))}", "Wall velocities"
    elif kind == "extreme":
        value, entry = f"x-: {fmt([0.0, rng.choice([1e308, -1e308, 1e10])] + [0.0] * (dim - 2))}", "Wall velocities"
    elif kind == "garbled":
        value, entry = rng.choice(["y+", "y+:", ": 1, 0", "y+ 1, 0", "y+: 1, 0;;y-: 0, 0", ";"]), "Wall velocities"
    elif kind == "double":
        value, entry = f"y+: {fmt([1.0] + [0.0] * (dim - 1))}; y+: {fmt([2.0] + [0.0] * (dim - 1))}", "Wall velocities"
    elif kind == "periodic all":
        value, entry = ", ".join("xyz"[:dim]), "Periodic directions"
    else:
        value, entry = rng.choice(["x, x", "q", "xy", "z" if dim == 2 else "w", ",", "x;y"]), "Periodic directions"
    path = ("Boundary conditions",) if entry == "Wall velocities" else ("Geometry",)
    scene.set(path, entry, value)
    return f"{entry} ({kind}) = {value!r}"


def m_structure(rng, scene, ctx):
    kind = rng.choice(["drop end", "extra end", "unknown subsection", "no equals", "no set",
                       "crlf", "tab", "non-utf8", "nul", "unclosed", "empty name", "long line"])
    lines = scene.lines
    ends = [i for i, l in enumerate(lines) if l.strip() == "end"]
    subs = [i for i, l in enumerate(lines) if l.strip().startswith("subsection ")]
    sets = [e[0] for e in scene.entries()]
    if kind == "drop end" and ends:
        del lines[rng.choice(ends)]
    elif kind == "extra end":
        lines.insert(rng.randrange(len(lines) + 1), "end")
    elif kind == "unknown subsection":
        lines += ["subsection Nonsense", "  set Foo = 1", "end"]
    elif kind == "no equals" and sets:
        i = rng.choice(sets)
        lines[i] = lines[i].replace("=", " ", 1)
    elif kind == "no set" and sets:
        i = rng.choice(sets)
        lines[i] = lines[i].replace("set ", "", 1)
    elif kind == "crlf":
        scene.lines = [l + "\r" for l in lines]
    elif kind == "tab" and sets:
        i = rng.choice(sets)
        lines[i] = lines[i].replace(" ", "\t")
    elif kind == "non-utf8" and sets:
        i = rng.choice(sets)
        lines[i] = lines[i] + "\udcff\udcfe"
    elif kind == "nul" and sets:
        i = rng.choice(sets)
        lines[i] = lines[i].replace("=", "=\0", 1)
    elif kind == "unclosed" and subs:
        lines.append("subsection " + lines[rng.choice(subs)].strip()[len("subsection "):])
    elif kind == "empty name":
        lines.append("set = 1")
    elif kind == "long line" and sets:
        i = rng.choice(sets)
        lines[i] = lines[i] + " " + "9" * 100000
    else:
        return None
    return f"structure ({kind})"


def m_files(rng, scene, ctx):
    """Output and checkpoint places that cannot be used, and resuming without a checkpoint."""
    kind = rng.choice(["output is a file", "output below a file", "long name", "spaces",
                       "checkpoint is a file", "resume", "resume below a file", "interval",
                       "unicode", "output = checkpoint"])
    if kind == "output is a file":
        scene.set(("Output",), "Directory", "mutant.prm")
    elif kind == "output below a file":
        scene.set(("Output",), "Directory", "mutant.prm/out")
    elif kind == "long name":
        scene.set(("Output",), "Directory", "o" * rng.choice([255, 256, 5000]))
    elif kind == "spaces":
        scene.set(("Output",), "Directory", "my output dir")
    elif kind == "checkpoint is a file":
        scene.set(("Checkpointing",), "Directory", "mutant.prm")
        scene.set(("Checkpointing",), "Interval", "1")
    elif kind == "resume":
        scene.set(("Checkpointing",), "Resume", "true")
    elif kind == "resume below a file":
        scene.set(("Checkpointing",), "Directory", "mutant.prm/checkpoint")
        scene.set(("Checkpointing",), "Resume", "true")
    elif kind == "interval":
        scene.set(("Checkpointing",), "Interval", rng.choice(["1", "0", "-1", "4294967296"]))
    elif kind == "unicode":
        scene.set(("Output",), "Directory", "ausgabe-\u00e4\u00f6\u00fc")
    else:
        scene.set(("Checkpointing",), "Directory", OUTPUT_NAME)
        scene.set(("Checkpointing",), "Interval", "1")
    return f"files ({kind})"


MUTATORS = [(m_delete, 3), (m_duplicate, 2), (m_garble, 5), (m_extreme, 6), (m_vector, 3),
            (m_particles, 5), (m_refinement, 4), (m_time, 4), (m_dimension, 1), (m_box, 2),
            (m_walls, 2), (m_structure, 2), (m_files, 2)]


def mutate(rng, scene, ctx):
    names, weights = zip(*MUTATORS)
    descriptions = []
    # One change in most mutants, so a failure points at one cause; some get two.
    for _ in range(2 if rng.random() < 0.15 else 1):
        for _attempt in range(10):
            d = rng.choices(names, weights)[0](rng, scene, ctx)
            if d:
                descriptions.append(d)
                break
    return "; ".join(descriptions)


# ---------------------------------------------------------------------------------------
# Running and classifying
# ---------------------------------------------------------------------------------------
ABORT_MARKERS = ["MPI_ABORT", "mpirun has exited due to", "Primary job terminated",
                 "Stacktrace", "stacktrace", "backtrace", "Backtrace", "-----",
                 "An error occurred in line", "terminate called", "Segmentation fault",
                 "Aborted", "core dumped", "Signal:", "exited on signal", "Abort(", "BAD TERMINATION",
                 "Additional information", "The violated condition"]
MEMORY_MARKERS = ["bad_alloc", "out of memory", "Cannot allocate memory", "tried to allocate",
                  "std::length_error", "INFOG(1) = -13"]
# What Open MPI's mpirun prints whenever a rank exits non-zero, also after a clean error
# exit on every rank: its report of the exit status, not an abort. MPI_Abort and a rank
# that dies print other text, which the markers above catch.
MPIRUN_EXIT_NOTICE = re.compile(
    r"-{20,}\nPrimary job +terminated normally, but \d+ process(es)? returned\na non-zero exit "
    r"code\. Per user-direction, the job has been aborted\.\n-{20,}\n"
    r"(-{20,}\nmpirun detected that one or more processes exited with non-zero status, thus "
    r"causing\nthe job to be terminated\. The first process to do so was:\n\n +Process name: "
    r"\S+\n +Exit code: +\d+\n-{20,}\n)?")
NON_FINITE = re.compile(r"(?i)\b[+-]?(nan|inf|infinity)\b")


def check_csv(path):
    """A problem with the CSV file, or None."""
    try:
        with open(path, "rb") as f:
            data = f.read()
        text = data.decode("utf-8")
    except (OSError, UnicodeDecodeError) as e:
        return f"{os.path.basename(path)} unreadable ({e})"
    name = os.path.basename(path)
    if not text:
        return f"{name} is empty"
    if not text.endswith("\n"):
        return f"{name} ends in the middle of a line"
    lines = text.splitlines()
    width = len(lines[0].split(","))
    if not lines[0] or any(not c.strip() for c in lines[0].split(",")):
        return f"{name} has no header"
    for k, line in enumerate(lines[1:], 2):
        if len(line.split(",")) != width:
            return f"{name} line {k} has {len(line.split(','))} fields, the header {width}"
        if NON_FINITE.search(line):
            return f"{name} line {k} holds a non-finite number: {line[:120]}"
    return None


def check_output(out_dir, require_tables):
    """Problems with a run's output directory."""
    problems = []
    for table in ("particles.csv", "statistics.csv"):
        if not os.path.exists(os.path.join(out_dir, table)):
            if require_tables:
                problems.append(f"{table} missing in the output directory")
            else:
                problems.append(f"half-written output: {table} missing")
    for path in sorted(glob.glob(os.path.join(out_dir, "*.csv"))):
        p = check_csv(path)
        if p:
            problems.append(p)
    return problems


def classify(rc, stdout, stderr, out_dir, timed_out):
    """(ok, reason) for one run."""
    if timed_out:
        last = [l for l in stdout.splitlines() if l.strip()][-1:] or ["(no output)"]
        return False, f"timeout (last stdout line: {last[0][:150]})"
    if rc < 0 or rc > 128:
        sig = -rc if rc < 0 else rc - 128
        return False, f"killed by signal {sig}" + (" (memory limit?)" if sig in (6, 9, 11) else "")
    everything = stdout + stderr
    for m in MEMORY_MARKERS:
        if m in everything:
            return False, f"out of memory ({m!r}); the input should have been refused"
    stderr = MPIRUN_EXIT_NOTICE.sub("", stderr)
    error_lines = [l for l in stderr.splitlines() if l.startswith("fdparticle: error")]
    other = [l for l in stderr.splitlines() if l.strip() and not l.startswith("fdparticle: error")]
    if rc == 0:
        if error_lines or other:
            return False, f"exit 0 with output on stderr: {(error_lines + other)[0][:150]!r}"
        if not os.path.isdir(out_dir):
            return False, "exit 0 without an output directory"
        problems = check_output(out_dir, True)
        return (not problems), "; ".join(problems) or "ran"
    for m in ABORT_MARKERS:
        if m in stderr:
            return False, f"abort report on stderr ({m!r}): {stderr.strip().splitlines()[0][:150]}"
    if len(error_lines) != 1:
        return False, f"{len(error_lines)} 'fdparticle: error' lines (exit {rc}): {stderr.strip()[:200]!r}"
    if other:
        return False, f"stderr has more than the error line: {other[0][:150]!r}"
    message = error_lines[0][len("fdparticle: error"):].lstrip(":").strip()
    if len(message) < 15 or "unknown exception" in message:
        return False, f"error line says too little: {error_lines[0][:150]!r}"
    if os.path.isdir(out_dir):
        problems = check_output(out_dir, False)
        if problems:
            return False, "error, and " + "; ".join(problems)
    return True, "error: " + message[:100]


def limit_memory(limit_bytes):
    def apply():
        resource.setrlimit(resource.RLIMIT_AS, (limit_bytes, limit_bytes))
        resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
    return apply


def run(opts, prm, cwd, ranks, timeout=None):
    """(rc, stdout, stderr, timed_out, seconds); timeout: seconds per rank (default
    --timeout)."""
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               DEAL_II_NUM_THREADS="1", OMP_NUM_THREADS="1")
    cmd = [opts.executable, prm]
    if ranks > 1:
        cmd = ["bash", MPIRUN, str(ranks)] + cmd
    start = time.time()
    # A process group of its own: on a time-out the whole tree (mpirun and its ranks) is ended.
    proc = subprocess.Popen(cmd, cwd=cwd, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            preexec_fn=limit_memory(int(opts.memory * 2 ** 30)),
                            start_new_session=True)
    try:
        # Oversubscribed ranks share the cores: a parallel run gets the time of each rank.
        out, err = proc.communicate(timeout=(timeout or opts.timeout) * ranks)
        timed_out = False
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        out, err = proc.communicate()
        timed_out = True
    decode = lambda b: b.decode("utf-8", errors="replace")
    return proc.returncode, decode(out), decode(err), timed_out, time.time() - start


def prepare(opts, name, scene_text, directory):
    """Write the mutant below 'directory' (fixtures copied in); return the prm path."""
    shutil.rmtree(directory, ignore_errors=True)
    os.makedirs(directory)
    if "@TESTS@" in scene_text:
        fixtures = os.path.join(directory, "fixtures")
        for sub in set(re.findall(r"@TESTS@/([^/\s]+)", scene_text)):
            if os.path.isdir(os.path.join(TESTS, sub)):
                shutil.copytree(os.path.join(TESTS, sub), os.path.join(fixtures, sub))
        scene_text = scene_text.replace("@TESTS@", fixtures)
    prm = os.path.join(directory, "mutant.prm")
    with open(prm, "wb") as f:
        f.write(scene_text.encode("utf-8", errors="surrogateescape"))
    return prm


def output_directory(scene_text, directory):
    value = Scene(scene_text.splitlines()).value(("Output",), "Directory", "output")
    return os.path.join(directory, value.strip())


def save_failure(opts, label, text, ranks, reason, stderr):
    failures = os.path.join(opts.work, "failures")
    os.makedirs(failures, exist_ok=True)
    base = os.path.join(failures, label)
    with open(base + ".prm", "wb") as f:
        f.write(text.encode("utf-8", errors="surrogateescape"))
    with open(base + ".txt", "w") as f:
        runner = f"bash scripts/mpirun.sh {ranks} " if ranks > 1 else ""
        f.write(f"{reason}\n\nreproduce in this directory (replace @TESTS@ by the tests/ "
                f"directory):\n  {runner}fdparticle {label}.prm\n\nstderr:\n{stderr[-3000:]}\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--count", type=int, default=100,
                        help="mutants to run (0: no limit, stop at --duration)")
    parser.add_argument("--duration", type=float, default=0,
                        help="stop starting mutants after this many seconds (0: no limit)")
    parser.add_argument("--work", default=os.path.join(TOP, "benchmarks", "work", "fuzz"))
    parser.add_argument("--executable", default=os.path.join(TOP, "build", "fdparticle"))
    parser.add_argument("--timeout", type=float, default=60,
                        help="seconds per run (per rank: N ranks share the cores)")
    parser.add_argument("--ranks", type=int, default=2,
                        help="MPI ranks of the parallel runs (1: none)")
    parser.add_argument("--parallel-fraction", type=float, default=0.2,
                        help="fraction of the mutants run on --ranks ranks")
    parser.add_argument("--memory", type=float, default=4, help="address-space limit per process, GiB")
    parser.add_argument("--steps", type=int, default=2, help="time steps a scene is cut to")
    parser.add_argument("--scenes", nargs="*", default=list(SCENE_GLOBS),
                        help="globs of base scenes, relative to the repository")
    parser.add_argument("--max-base-seconds", type=float, default=20,
                        help="leave out scenes whose shortened, unchanged run takes longer")
    parser.add_argument("--keep", action="store_true", help="keep the directories of passing runs")
    opts = parser.parse_args()
    opts.executable = os.path.abspath(opts.executable)
    opts.work = os.path.abspath(opts.work)
    shutil.rmtree(opts.work, ignore_errors=True)
    os.makedirs(opts.work)
    started = time.time()
    rng = random.Random(opts.seed)
    declared = [(tuple(p), n, v) for p, n, v in declared_parameters(opts.executable)]
    ctx = {"declared": declared, "defaults": {(p, n): v for p, n, v in declared}}

    # Baselines: each scene shortened but unchanged must pass too; slow ones are left out.
    scenes, base_seconds, failed = {}, {}, 0
    for name, lines in shipped_scenes(opts.scenes).items():
        scene = capped(lines, opts.steps, ctx["defaults"])
        directory = os.path.join(opts.work, "base", name.replace("/", "_"))
        prm = prepare(opts, name, scene.text(), directory)
        rc, out, err, timed_out, seconds = run(opts, prm, directory, 1,
                                               max(opts.timeout, opts.max_base_seconds))
        ok, reason = classify(rc, out, err, output_directory(scene.text(), directory), timed_out)
        if not ok and not timed_out:  # a slow scene is left out below, not a failure
            failed += 1
            print(f"FAIL base {name}: {reason}", flush=True)
            save_failure(opts, "base-" + name.replace("/", "_")[:-4], scene.text(), 1, reason, err)
        if seconds <= opts.max_base_seconds and not timed_out:
            scenes[name] = scene.lines
            base_seconds[name] = seconds
        else:
            print(f"left out {name}: its shortened run took {seconds:.0f} s", flush=True)
        if not opts.keep:
            shutil.rmtree(directory, ignore_errors=True)
    print(f"{len(scenes)} base scenes; {failed} failed unchanged", flush=True)
    if not scenes:
        return 1

    names = sorted(scenes)
    n_ok = n_failed = n_ran = 0
    reasons = {}
    i = 0
    while (opts.count == 0 or i < opts.count) and \
          (opts.duration == 0 or time.time() - started < opts.duration):
        i += 1
        name = rng.choice(names)
        scene = Scene(scenes[name])
        description = mutate(rng, scene, ctx)
        ranks = opts.ranks if opts.ranks > 1 and rng.random() < opts.parallel_fraction else 1
        text = f"# fuzz mutant {i} of {name} (seed {opts.seed}): {description}\n" + scene.text()
        directory = os.path.join(opts.work, f"mutant-{i:05d}")
        prm = prepare(opts, name, text, directory)
        # A hang is a run far slower than its unchanged scene was just now: on a busy machine
        # both are slow, so the limit grows with the base run's time.
        timeout = max(opts.timeout, HANG_FACTOR * base_seconds[name])
        rc, out, err, timed_out, seconds = run(opts, prm, directory, ranks, timeout)
        ok, reason = classify(rc, out, err, output_directory(text, directory), timed_out)
        if not os.path.isfile(prm):
            ok, reason = False, "the run replaced or deleted its own parameter file"
        if ok:
            n_ok += 1
            n_ran += (rc == 0)
        else:
            n_failed += 1
            label = f"mutant-{i:05d}"
            print(f"FAIL {label} {name} np={ranks} [{description}]: {reason}", flush=True)
            save_failure(opts, label, text, ranks, reason, err)
            key = re.sub(r"[-+]?\d[\d.e+-]*", "N", reason.split(":")[0])[:60]
            reasons[key] = reasons.get(key, 0) + 1
        if ok and not opts.keep:
            shutil.rmtree(directory, ignore_errors=True)
    elapsed = time.time() - started
    for key, n in sorted(reasons.items(), key=lambda kv: -kv[1]):
        print(f"  {n:5d} x {key}")
    print(f"{i} mutants: {n_ok} ok, {n_failed} failed ({n_ran} ran to the end, {n_ok - n_ran} "
          f"stopped with one error line; {elapsed:.0f} s, seed {opts.seed}, {len(names)} base "
          f"scenes)", flush=True)
    return 1 if (n_failed or failed) else 0


if __name__ == "__main__":
    sys.exit(main())
