"""Helpers for tests/NAME/check.py scripts: read fdparticle's CSV output, assert with context."""
import csv
import datetime
import os
import sys


def table(out_dir, name):
    """Rows of OUT_DIR/NAME as dicts of floats."""
    with open(os.path.join(out_dir, name), newline="") as f:
        return [{k: float(v) for k, v in row.items()} for row in csv.DictReader(f)]


_failures = []


def check(condition, message):
    print(("ok:   " if condition else "FAIL: ") + message, flush=True)
    if not condition:
        _failures.append(message)
    return condition


def failed():
    """The number of failed checks so far."""
    return len(_failures)


def finish():
    sys.exit(1 if _failures else 0)


def prm_entries(text):
    """{'Subsection/Name': value} of the text of a parameter file; a later 'set' of an
    entry wins, as in deal.II's ParameterHandler."""
    values, path = {}, []
    for line in text.splitlines():
        # Any white space separates the keywords, as in ParameterHandler.
        line = line.split("#")[0].strip()
        words = line.split(None, 1)
        if len(words) == 2 and words[0] == "subsection":
            path.append(words[1].strip())
        elif line == "end":
            path.pop()
        elif len(words) == 2 and words[0] == "set":
            name, value = words[1].split("=", 1)
            values["/".join(path + [" ".join(name.split())])] = value.strip()
    return values


def parameters(out_dir):
    """The entries of OUT_DIR/parameters.prm (written by fdparticle) as
    {'Subsection/Name': value}."""
    with open(f"{out_dir}/parameters.prm") as f:
        return prm_entries(f.read())


def run_provenance(out_dir):
    """(date, revision) of the finished run in OUT_DIR: when its particles.csv was last
    written (UTC) and the build named on the first line of its parameters.prm ('# Written
    by fdparticle REVISION (...)'). A benchmark that reuses a run reports both."""
    with open(f"{out_dir}/parameters.prm") as f:
        words = f.readline().split()
    revision = words[4] if words[:4] == ["#", "Written", "by", "fdparticle"] and len(words) > 4 else "unknown"
    when = os.path.getmtime(f"{out_dir}/particles.csv")
    return (datetime.datetime.fromtimestamp(when, datetime.timezone.utc).strftime("%Y-%m-%dT%H:%MZ"),
            revision)


# ------------------------------------------------------------------ comparing two runs
# How two runs of a scene are compared, number by number (ranks, restart, solvers, mirror,
# shift, stored output; tests/README.md states the rule): a value may differ by
#     |a - b| <= REL * max(|a|, |b|) + FLOOR * S   (or one unit of its last written digit),
# S the scale of its column over both runs. Round-off moves with the order of operations,
# which changes with the partition and, on several ranks, with the parallel factorization's
# dynamic scheduling; it is a fraction of the largest value of a kind, so a component that
# is zero by symmetry is compared against its kind's scale, not against an absolute number.
AXES = "xyz"
# FLOOR when a test does not set it: about a hundred times the round-off that moves with
# the partition and with the timing of MUMPS's scheduling (up to 7e-12 of a column's
# scale in bounce_2d), and small enough that a relative error of 1e-6 in a column that is
# not near zero still fails.
FLOOR = 1e-9
# Columns that share a scale: the components of a vector; positions share the box size.
VECTOR_FAMILIES = ("v", "f", "contact_f", "mean_v", "mean_particle_v", "w", "t", "rot")


def column_family(name):
    """The kind of a column: 'position' for x, y, z; 'v' for vx, 'contact_f' for
    contact_fy, ...; the name itself for a scalar column."""
    if name in AXES:
        return "position"
    if len(name) >= 2 and name[-1] in AXES and name[:-1] in VECTOR_FAMILIES:
        return name[:-1]
    return name


def column_scales(header, runs, box=None, radius=None):
    """{column: S} for rows of floats (or numeric strings) of one or more runs with the same
    header: S is the largest magnitude of the column's kind over all runs; positions are
    measured against the box size (box), and, given the smallest particle radius, angular
    velocities and torques also against what the translation makes of them (|v|/R, |f| R)
    and the other way round (|w| R, |t|/R),
    contact forces against the hydrodynamic force and rotation angles against one radian."""
    family = {h: column_family(h) for h in header}
    scale = {}
    for rows in runs:
        for row in rows:
            for h, value in zip(header, row):
                try:
                    value = abs(float(value))
                except ValueError:
                    continue
                if value == value and value != float("inf"):
                    scale[family[h]] = max(scale.get(family[h], 0.0), value)
    if box is not None:
        scale["position"] = box
    if radius:
        v, w, f, t = (scale.get(k, 0.0) for k in ("v", "w", "f", "t"))
        scale["w"], scale["v"] = max(w, v / radius), max(v, w * radius)
        scale["t"], scale["f"] = max(t, f * radius), max(f, t / radius)
    scale["contact_f"] = max(scale.get("contact_f", 0.0), scale.get("f", 0.0))
    scale["rot"] = max(scale.get("rot", 0.0), 1.0)
    return {h: scale.get(family[h], 0.0) for h in header}


def allowed_difference(a, b, rel, floor, scale):
    """The largest |a - b| two runs may differ by (the rule above)."""
    return rel * max(abs(a), abs(b)) + floor * scale


def printed_unit(text):
    """One unit in the last digit of a number as written ('-0.0051174' -> 1e-7,
    '2.98e-07' -> 1e-9; 0 for an integer): the CSV files hold 12 significant digits, so
    two values that differ by round-off may be written one unit apart, whatever the
    tolerance."""
    mantissa, e, exponent = text.strip().lower().partition("e")
    if not e and "." not in mantissa:
        return 0.0  # an integer (a count, an index, an exact zero) is exact
    decimals = len(mantissa.partition(".")[2])
    try:
        return 10.0 ** (int(exponent or 0) - decimals)
    except ValueError:
        return 0.0


def box_size(entries):
    """The largest edge of the box of a prm's entries (testlib.prm_entries), or None."""
    try:
        lower = [float(v) for v in entries["Geometry/Lower corner"].split(",")]
        upper = [float(v) for v in entries["Geometry/Upper corner"].split(",")]
    except KeyError:
        return None
    return max(u - l for l, u in zip(lower, upper))
