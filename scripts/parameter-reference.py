#!/usr/bin/python3
"""Write the parameter reference doc/parameters.md from `fdparticle --print-parameters`.

    scripts/parameter-reference.py build/fdparticle > doc/parameters.md

The program's own declarations (name, default, documentation string) are the only source,
so the reference cannot drift from the code: tests/docs/check_docs.py regenerates it and
fails when the checked-in file differs.
"""
import subprocess
import sys


def parse_listing(text):
    """Entries of a deal.II PRM listing as (subsection path, name, default, documentation).

    In the listing each `set` line is preceded by its documentation as `#` comment lines;
    nothing has been parsed, so the value shown is the default.
    """
    entries = []
    path = []
    comment = []
    for raw in text.splitlines():
        line = raw.strip()
        if line.startswith("#"):
            text = line[1:].strip()
            # The listing's title is underlined with dashes; it documents no entry.
            comment = [] if text and set(text) == {"-"} else comment + [text]
        elif line.startswith("subsection "):
            path.append(line[len("subsection "):].strip())
            comment = []
        elif line == "end":
            path.pop()
            comment = []
        elif line.startswith("set "):
            name, _, value = line[len("set "):].partition("=")
            entries.append((tuple(path), name.strip(), value.strip(), " ".join(comment)))
            comment = []
        elif not line:
            comment = []
    return entries


def cell(text):
    return text.replace("|", "\\|")


def reference(entries):
    out = ["# Parameter reference",
           "",
           "Every entry of an fdparticle parameter file, its default and its meaning, as the",
           "program declares them (`fdparticle --print-parameters`). Generated; do not edit.",
           "Regenerate after changing a declaration:",
           "",
           "    scripts/parameter-reference.py build/fdparticle > doc/parameters.md",
           "",
           "The ctest `docs` fails while this file differs from what the program declares.",
           "How to write a parameter file: [README.md](../README.md#the-parameter-file).",
           ""]
    sections = []
    for path, *_ in entries:
        if path not in sections:
            sections.append(path)
    for path in sections:
        out.append("## " + (" / ".join(path) if path else "Top level"))
        out.append("")
        out.append("| entry | default | meaning |")
        out.append("|---|---|---|")
        for p, name, default, doc in entries:
            if p == path:
                shown = "`" + default + "`" if default else "(empty)"
                out.append("| `%s` | %s | %s |" % (name, cell(shown), cell(doc)))
        out.append("")
    return "\n".join(out)


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: parameter-reference.py FDPARTICLE_EXECUTABLE")
    listing = subprocess.run([sys.argv[1], "--print-parameters"], check=True,
                             capture_output=True, text=True).stdout
    sys.stdout.write(reference(parse_listing(listing)))


if __name__ == "__main__":
    main()
