#!/usr/bin/env python3
"""Lists the functions of src/ longer than a limit (docs/testing.md, house
rules): a definition that starts at column 0 and ends at the first line that
is a lone `}` at column 0. Exits 1 when any is over the limit.
Usage: function_lengths.py SRC_DIR [LIMIT]"""
import pathlib
import re
import sys

NOT_FUNCTIONS = re.compile(r"^(namespace|struct|class|enum|union|extern|template\s*<[^>]*>\s*(struct|class))\b")


def long_functions(path, limit):
    """(line, length, head) of each over-long definition in `path`. A head
    starts at column 0 and may span lines up to the one ending in `{`."""
    lines = path.read_text(encoding="utf-8").splitlines()
    head = start = None
    for i, line in enumerate(lines):
        if start is None:
            at_column0 = line[:1] not in ("", " ", "\t", "#", "/", "}", "*")
            if at_column0 and not NOT_FUNCTIONS.match(line) and "(" in line:
                head = i
            if head is not None:
                if line.rstrip().endswith(";") or (line[:1] in ("", "#", "/") and i != head):
                    head = None
                elif line.rstrip().endswith("{"):
                    start, head = head, None
        elif line == "}" or line.startswith("}  //") or line == "};":
            length = i - start + 1
            if length > limit:
                yield start + 1, length, lines[start].strip()
            start = None


def main():
    src = pathlib.Path(sys.argv[1])
    limit = int(sys.argv[2]) if len(sys.argv) > 2 else 80
    found = 0
    for path in sorted(src.rglob("*")):
        if path.suffix not in (".cpp", ".hpp"):
            continue
        for line, length, head in long_functions(path, limit):
            print(f"{path.relative_to(src.parent)}:{line}: {length} lines: {head}")
            found += 1
    if found:
        print(f"function_lengths: {found} functions over {limit} lines", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
