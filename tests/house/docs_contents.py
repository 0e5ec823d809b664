#!/usr/bin/env python3
"""Every `## ` section of a document is listed in its Contents, in order, with
the anchor GitHub gives it (docs/testing.md, house rules).
Usage: docs_contents.py FILE.md..."""
import re
import sys


def anchor(heading):
    """GitHub's anchor: lower case, punctuation but - and _ dropped, spaces to -."""
    return re.sub(r"[^\w\- ]", "", heading.strip().lower()).replace(" ", "-")


def problems(path):
    text = open(path, encoding="utf-8").read()
    if "\n## Contents\n" not in text:
        return []
    contents = text.split("\n## Contents\n", 1)[1].split("\n## ", 1)[0]
    listed = re.findall(r"^- \[([^\]]+)\]\(#([^)]+)\)", contents, re.M)
    sections = [h for h in re.findall(r"^## (.+)$", text, re.M) if h != "Contents"]
    out = []
    if [h for h, _ in listed] != sections:
        out.append(f"{path}: Contents {[h for h, _ in listed]} != sections {sections}")
    out += [f"{path}: '{h}' links #{a}, its anchor is #{anchor(h)}" for h, a in listed if a != anchor(h)]
    return out


if __name__ == "__main__":
    found = [p for f in sys.argv[1:] for p in problems(f)]
    print("\n".join(found))
    sys.exit(1 if found else 0)
