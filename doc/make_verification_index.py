#!/usr/bin/env python3
"""Write the index table of doc/verification.md from its case sections.

Every case section (a '### ' heading) starts with the lines

    - **Test**: `dir/name`, ...
    - **Reference**: ...
    - **Input**: ...
    - **Result**: ...
    - **Status**: ...

The index (case, test, reference, result, status) is written between the
markers '<!-- index start -->' and '<!-- index end -->'. Every test named
as `dir/name` in a **Test** line must exist in tests/dir/ (name.prm,
name.prm.in, name.cc, or a glob pattern matching one of them).

    python3 doc/make_verification_index.py          # rewrite the index
    python3 doc/make_verification_index.py --check  # exit 1 if stale or a test is missing
"""
import glob
import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
DOC = os.path.join(HERE, "verification.md")
TESTS = os.path.join(HERE, "..", "tests")
START, END = "<!-- index start -->", "<!-- index end -->"
KEYS = ("Test", "Reference", "Input", "Result", "Status")


def slug(heading):
    """GitHub's anchor for a heading."""
    s = heading.strip().lower()
    s = re.sub(r"[^\w\- ]", "", s)
    return s.replace(" ", "-")


def sections(text):
    """(part, heading, {key: value}) for every case section."""
    part, out, lines = "", [], text.split("\n")
    for i, line in enumerate(lines):
        if line.startswith("## "):
            part = line[3:].strip()
        elif line.startswith("### "):
            fields = {}
            for follow in lines[i + 1:i + 8]:
                m = re.match(r"- \*\*(\w+)\*\*: (.*)", follow)
                if m and m.group(1) in KEYS:
                    fields[m.group(1)] = m.group(2).strip()
            if "Test" in fields and "Status" in fields:
                out.append((part, line[4:].strip(), fields))
    return out


def missing_tests(cases):
    missing = []
    for _, heading, fields in cases:
        for name in re.findall(r"`([a-z]+/[^`\s]+)`", fields["Test"]):
            directory, base = name.split("/", 1)
            if not os.path.isdir(os.path.join(TESTS, directory)):
                continue  # a path outside tests/, e.g. contrib/...
            pattern = os.path.join(TESTS, directory, base)
            found = [f for f in glob.glob(pattern + "*")
                     if re.search(r"\.(prm|prm\.in|cc)$", f)]
            if not found:
                missing.append(f"{heading}: {name}")
    return missing


def index(cases):
    rows = ["| case | test | reference | result | status |",
            "|---|---|---|---|---|"]
    part = None
    for p, heading, f in cases:
        if p != part:
            rows.append(f"| **{p}** | | | | |")
            part = p
        cell = lambda k: f.get(k, "").replace("|", "\\|")
        rows.append(f"| [{heading}](#{slug(heading)}) | {cell('Test')} | "
                    f"{cell('Reference')} | {cell('Result')} | {cell('Status')} |")
    return "\n".join(rows)


def main():
    text = open(DOC, encoding="utf-8").read()
    if START not in text or END not in text:
        sys.exit(f"{DOC}: markers {START} / {END} not found")
    cases = sections(text)
    head, rest = text.split(START, 1)
    _, tail = rest.split(END, 1)
    new = head + START + "\n" + index(cases) + "\n" + END + tail
    missing = missing_tests(cases)
    for m in missing:
        print(f"test not found in tests/: {m}", file=sys.stderr)
    if "--check" in sys.argv:
        if new != text:
            print("doc/verification.md: the index is out of date: "
                  "run python3 doc/make_verification_index.py", file=sys.stderr)
        sys.exit(1 if (new != text or missing) else 0)
    open(DOC, "w", encoding="utf-8").write(new)
    print(f"doc/verification.md: index of {len(cases)} cases written")
    sys.exit(1 if missing else 0)


if __name__ == "__main__":
    main()
