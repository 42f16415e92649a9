#!/usr/bin/python3
"""The documentation says what the program and the suite are.

Fails when
- doc/parameters.md differs from what scripts/parameter-reference.py writes from the
  program's declarations (regenerate it with the command the failure prints);
- a new run into an output directory leaves the field files of an earlier run there, or
  removes a file the program does not write;
- `fdparticle --version` does not name the revision, deal.II's version and the build type,
  or parameters.prm does not start with it;
- a CSV file the program writes has no section in doc/output.md (a heading naming the
  file) that gives its exact header line and names each of its columns;
- tests/README.md does not give the number of tests ctest has, or does not name one of
  them;
- a relative link in README.md or a page doc/*.md (`[text](path)`, `[text](path#anchor)`,
  `[text](#anchor)`, `[label]: path`) names a file that does not exist or, into a
  Markdown file, a heading that does not exist (GitHub's anchors: lower case, spaces to
  '-', punctuation dropped);
- a path in one of README.md's code blocks (prm/..., benchmarks/..., tools/...,
  scripts/..., doc/..., ...) does not exist in the repository;
- a reference page (README.md and every doc/*.md but doc/history.md) carries a date
  (YYYY-MM-DD) or a git commit hash (7-40 lower-case hex digits, at least one letter and
  one digit) outside its code blocks, URLs and comma-joined (CSV) text: the page says what
  holds now; the CSV files carry the date and commit of each row, git the history.
"""
import argparse
import difflib
import os
import re
import shutil
import subprocess
import sys
import urllib.parse

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


OUTPUT_PAGE = os.path.join("doc", "output.md")


def file_section(page, name):
    """The text under the heading that names the file 'name', down to the next heading of
    the same or a higher level; "" if there is none."""
    lines = page.splitlines()
    for i, line in enumerate(lines):
        heading = re.match(r"^(#+)\s+(.*)$", line)
        if heading and re.search(r"(?<![\w.])%s(?![\w.])" % re.escape(name),
                                 heading.group(2).replace("`", "")):
            level = len(heading.group(1))
            body = []
            for following in lines[i + 1:]:
                other = re.match(r"^(#+)\s", following)
                if other and len(other.group(1)) <= level:
                    break
                body.append(following)
            return "\n".join(body)
    return ""


def check_csv_columns(source, executable, work):
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    with open(os.path.join(work, "scene.prm"), "w") as f:
        f.write(SCENE)
    # Files of an earlier, longer run into the same directory, and one of the user's.
    os.makedirs(os.path.join(work, "output"))
    stale = ["solution-00099.pvtu", "solution-00099.0000.vtu", "particles-00099.vtu"]
    for name in stale + ["notes.txt"]:
        open(os.path.join(work, "output", name), "w").close()
    subprocess.run([executable, "scene.prm"], cwd=work, check=True, stdout=subprocess.DEVNULL)
    left = [name for name in stale if os.path.exists(os.path.join(work, "output", name))]
    check(not left and os.path.exists(os.path.join(work, "output", "notes.txt")),
          "a new run removes the field files of an earlier one and nothing else%s"
          % (" (left: %s)" % ", ".join(left) if left else ""))
    path = os.path.join(source, OUTPUT_PAGE)
    page = open(path).read() if os.path.exists(path) else ""
    check(page != "", "%s exists" % OUTPUT_PAGE)
    out_dir = os.path.join(work, "output")
    # The run names its build, as --version does (doc/output.md, parameters.prm).
    version = subprocess.run([executable, "--version"], check=True, capture_output=True,
                             text=True).stdout.strip()
    lines = version.split("\n")
    check(len(lines) == 2 and
          re.fullmatch(r"fdparticle \S+ \(deal\.II [0-9.]+, (Release|Debug)\)", lines[0]) is not None
          and re.fullmatch(r"BLAS: (not OpenBLAS|OpenBLAS \S+, \S+ kernels( \(.*\))?)", lines[1])
          is not None,
          "--version names the revision, deal.II, the build type and the BLAS: %s" % version)
    with open(os.path.join(out_dir, "parameters.prm")) as f:
        first = f.readline().strip()
    check(len(lines) == 2 and
          first == "# Written by %s on 1 MPI rank(s); %s" % (lines[0], lines[1]),
          "parameters.prm names the build and the BLAS that wrote it: %s" % first)
    csv_files = sorted(f for f in os.listdir(out_dir) if f.endswith(".csv"))
    check(len(csv_files) >= 3, "the scene wrote its CSV files (%s)" % ", ".join(csv_files))
    for name in csv_files:
        with open(os.path.join(out_dir, name)) as f:
            header = f.readline().strip()
        section = file_section(page, name)
        check(section != "", "%s has a section (a heading) for %s" % (OUTPUT_PAGE, name))
        check("`%s`" % header in section,
              "%s's section on %s gives its header: %s" % (OUTPUT_PAGE, name, header))
        missing = [c for c in header.split(",") if "`%s`" % c not in section]
        check(not missing, "%s's section on %s names every column%s"
              % (OUTPUT_PAGE, name, " (missing: %s)" % ", ".join(missing) if missing else ""))


# ------------------------------------------------------------------ links and paths
FENCE = re.compile(r"^\s*(```|~~~)")


def strip_code(text):
    """The text with fenced code blocks and inline code spans blanked out (their lines
    kept, so that line numbers still hold): a link inside code is not a link."""
    out, fenced = [], False
    for line in text.splitlines():
        if FENCE.match(line):
            fenced = not fenced
            out.append("")
            continue
        out.append("" if fenced else re.sub(r"(`+)(?:(?!\1).)+?\1", "", line))
    return out


def code_block_lines(text):
    """The lines of the fenced code blocks and of the indented code blocks (four spaces,
    after a blank line or another such line) of a Markdown text."""
    lines, fenced, indented, previous_blank = [], False, False, True
    for line in text.splitlines():
        if FENCE.match(line):
            fenced = not fenced
            continue
        if fenced:
            lines.append(line)
            continue
        if line.strip() == "":
            previous_blank = True
            continue
        if line.startswith("    ") and (previous_blank or indented):
            indented = True
            lines.append(line)
        else:
            indented = False
        previous_blank = False
    return lines


def github_anchor(heading):
    """GitHub's anchor of a heading's text: markup and punctuation dropped, lower case,
    each space a '-'."""
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", heading)  # a link: its text
    text = re.sub(r"<[^>]+>", "", text).strip().lower()
    return "".join(c for c in text if c.isalnum() or c in "-_ ").replace(" ", "-")


def anchors(path, cache={}):
    """The anchors of the headings of a Markdown file (repeated headings get -1, -2, ...)."""
    if path not in cache:
        found, seen = set(), {}
        with open(path, encoding="utf-8") as f:
            for line in strip_code_keep_headings(f.read()):
                for name in re.findall(r"<a\s+(?:name|id)=\"([^\"]+)\"", line):
                    found.add(name.lower())
                heading = re.match(r"^#{1,6}\s+(.*?)\s*#*\s*$", line)
                if not heading:
                    continue
                anchor = github_anchor(heading.group(1))
                n = seen.get(anchor, 0)
                seen[anchor] = n + 1
                found.add(anchor if n == 0 else "%s-%d" % (anchor, n))
        cache[path] = found
    return cache[path]


def strip_code_keep_headings(text):
    """The lines of a Markdown text outside fenced code blocks (a '#' line inside a code
    block is a comment, not a heading)."""
    out, fenced = [], False
    for line in text.splitlines():
        if FENCE.match(line):
            fenced = not fenced
            continue
        if not fenced:
            out.append(line)
    return out


LINK = re.compile(r"!?\[[^\]]*\]\(\s*<?([^)\s>]*)>?(?:\s+[\"'(][^)]*)?\)")
REFERENCE = re.compile(r"^\s{0,3}\[[^\]]+\]:\s*<?([^\s>]+)>?\s*(?:[\"'(].*)?$")


def markdown_pages(source):
    """README.md and the pages doc/*.md (the files below doc/ are generated tables and the
    parts doc/validation.md is assembled from, whose links are relative to doc/)."""
    doc = os.path.join(source, "doc")
    return [os.path.join(source, "README.md")] + [
        os.path.join(doc, f) for f in sorted(os.listdir(doc)) if f.endswith(".md")]


def broken_links(source, page):
    """(line number, target, what is wrong) for each relative link of the page that points
    nowhere."""
    broken = []
    with open(page, encoding="utf-8") as f:
        lines = strip_code(f.read())
    for number, line in enumerate(lines, 1):
        targets = LINK.findall(line) + REFERENCE.findall(line)
        for target in targets:
            if not target or re.match(r"^[a-zA-Z][a-zA-Z0-9+.-]*:", target):
                continue  # a URL (https:, mailto:, ...): not checked here
            path, _, anchor = target.partition("#")
            path = urllib.parse.unquote(path)
            resolved = page if path == "" else os.path.normpath(
                os.path.join(os.path.dirname(page), path))
            if not os.path.exists(resolved):
                broken.append((number, target, "no file %s"
                               % os.path.relpath(resolved, source)))
            elif anchor and resolved.endswith(".md") and os.path.isfile(resolved) \
                    and urllib.parse.unquote(anchor).lower() not in anchors(resolved):
                broken.append((number, target, "no heading #%s in %s"
                               % (anchor, os.path.relpath(resolved, source))))
    return broken


def check_links(source):
    for page in markdown_pages(source):
        broken = broken_links(source, page)
        name = os.path.relpath(page, source)
        check(not broken, "every relative link of %s points to a file and heading that exist%s"
              % (name, "".join("\n    %s:%d: (%s): %s" % (name, n, t, why)
                               for n, t, why in broken)))


# Paths that do not exist before a build or a run: the build trees, the output of scenes.
GENERATED = re.compile(r"^(build[^/]*|output)(/|$)")


def check_readme_paths(source):
    """Every path-like word (a/b..., starting with a top-level directory of the
    repository) in README.md's code blocks must exist."""
    tops = sorted(d for d in os.listdir(source)
                  if os.path.isdir(os.path.join(source, d)) and not d.startswith(".")
                  and not GENERATED.match(d))
    with open(os.path.join(source, "README.md"), encoding="utf-8") as f:
        lines = code_block_lines(f.read())
    words = set()
    for line in lines:
        line = line.split(" #")[0]  # a shell comment
        for word in re.split(r"[\s=]+", line):
            word = word.strip("\"'`,;:()[]")
            if word.startswith("./"):
                word = word[2:]
            if "/" in word and word.split("/")[0] in tops and not re.search(r"[{}*?$<>|]", word):
                words.add(word)
    check(len(lines) > 0, "README.md has code blocks")
    missing = sorted(w for w in words if not os.path.exists(os.path.join(source, w)))
    check(not missing, "every path in README.md's code blocks exists (%d checked)%s"
          % (len(words), " (missing: %s)" % ", ".join(missing) if missing else ""))


# ------------------------------------------------------------------ dates and commits
HISTORY_PAGE = os.path.join("doc", "history.md")
DATE = re.compile(r"(?<![\w-])(?:19|20)\d\d-(?:0[1-9]|1[0-2])-(?:0[1-9]|[12]\d|3[01])(?![\w-])")
# A hex word that stands alone: not part of a number (1.5e10, 2e-6), a path, an anchor, a
# name (x_1e3) or a comma-joined CSV row (0.1,abc1234,5).
HEX_WORD = re.compile(r"(?<![\w.,/#:+-])[0-9a-f]{7,40}(?![\w/+-]|[.,]\w)")
URL = re.compile(r"(?:https?|ftp)://\S+|\]\([^)]*\)|^\s{0,3}\[[^\]]+\]:\s*\S+|<[a-z]+:[^>]*>")


def is_hash(word):
    """At least one letter and one digit, and not a number in exponent notation (1e10000)."""
    return (re.search(r"[a-f]", word) is not None and re.search(r"\d", word) is not None
            and re.fullmatch(r"\d+e\d+", word) is None)


def prose_lines(text):
    """(line number, line) of a Markdown text outside its fenced code blocks and its
    indented code blocks (four spaces after a blank line, not a list item's text)."""
    out, fenced, indented, previous_blank, in_list = [], False, False, True, False
    for number, line in enumerate(text.splitlines(), 1):
        if FENCE.match(line):
            fenced = not fenced
            continue
        if fenced:
            continue
        if line.strip() == "":
            previous_blank = True
            continue
        if re.match(r"^\s{0,3}([-*+]|\d+[.)])\s", line):
            in_list = True
        elif not line.startswith(" "):
            in_list = False
        indented = (line.startswith("    ") and not in_list
                    and (previous_blank or indented))
        previous_blank = False
        if not indented:
            out.append((number, line))
    return out


def dates_and_hashes(path):
    """(line number, what) for each date or commit hash of a Markdown page outside its
    code blocks, URLs and link targets."""
    found = []
    with open(path, encoding="utf-8") as f:
        text = f.read()
    for number, line in prose_lines(text):
        line = URL.sub(" ", line)
        found += [(number, "date %s" % d) for d in DATE.findall(line)]
        found += [(number, "commit %s" % w) for w in HEX_WORD.findall(line) if is_hash(w)]
    return found


def check_no_dates_or_commits(source):
    for page in markdown_pages(source):
        name = os.path.relpath(page, source)
        if name == HISTORY_PAGE:
            continue
        found = dates_and_hashes(page)
        check(not found, "%s has no dates or commit hashes (they belong in the CSV files and "
              "git; what changed: %s)%s" % (name, HISTORY_PAGE, "".join(
                  "\n    %s:%d: %s" % (name, n, what) for n, what in found)))


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
    source = os.path.abspath(args.source)
    check_parameter_reference(source, executable)
    check_csv_columns(source, executable, args.work)
    check_test_list(source, args.build)
    check_links(source)
    check_readme_paths(source)
    check_no_dates_or_commits(source)
    finish()


if __name__ == "__main__":
    main()
