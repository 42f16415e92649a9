"""Helpers for tests/NAME/check.py scripts: read fdparticle's CSV output, assert with context."""
import csv
import os
import sys


def table(out_dir, name):
    """Rows of OUT_DIR/NAME as dicts of floats."""
    with open(os.path.join(out_dir, name), newline="") as f:
        return [{k: float(v) for k, v in row.items()} for row in csv.DictReader(f)]


_failures = []


def check(condition, message):
    print(("ok:   " if condition else "FAIL: ") + message)
    if not condition:
        _failures.append(message)


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
