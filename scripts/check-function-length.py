#!/usr/bin/env python3
"""Short functions: no function of the library, the CLI or the benchmarks over 150 lines, and at most 8
over 100 (docs/design.md, "Conventions"). Prints every function over 100 lines and exits 1 when the rule
is broken; exits 0 otherwise. Run from anywhere inside the checkout.

A function is a brace block opened at namespace scope (not a class, struct, enum or initializer), found
by matching braces after strings, character literals and comments are blanked: a count to read, not a
parser. Tests and third_party/ are left out.
"""
import re
import subprocess
import sys

MAX_LINES = 150
LONG_LINES = 100
MAX_LONG = 8


def blank_literals(source):
    source = re.sub(r'R"\((.|\n)*?\)"', '""', source)
    source = re.sub(r'"(\\.|[^"\\\n])*"', '""', source)
    source = re.sub(r"'(\\.|[^'\\\n])'", "''", source)
    return re.sub(r"//[^\n]*", "", source)


def function_lengths(path, source):
    """(lines, path, first line) of each brace block opened at namespace scope."""
    out = []
    depth = 0
    namespace_depths = []
    start = None
    head = ""
    for i, line in enumerate(blank_literals(source).split("\n")):
        for ch in line:
            if ch == "{":
                if re.match(r"^\s*(namespace|extern)\b", line):
                    namespace_depths.append(depth)
                elif depth == len(namespace_depths) and start is None:
                    before = line.split("{")[0]
                    if not re.match(r"^\s*(class|struct|enum|union)\b", line) and not before.rstrip().endswith("="):
                        start, head = i, line.strip()[:90]
                depth += 1
            elif ch == "}":
                depth -= 1
                if namespace_depths and namespace_depths[-1] == depth:
                    namespace_depths.pop()
                elif start is not None and depth == len(namespace_depths):
                    out.append((i - start + 1, path, head))
                    start = None
    return out


def main():
    root = subprocess.check_output(["git", "rev-parse", "--show-toplevel"], text=True).strip()
    files = subprocess.check_output(["git", "-C", root, "ls-files", "*.cc"], text=True).split()
    lengths = []
    for path in files:
        if path.startswith(("tests/", "third_party/")):
            continue
        with open(f"{root}/{path}", encoding="utf-8") as f:
            lengths += function_lengths(path, f.read())
    lengths.sort(reverse=True)
    long_ones = [f for f in lengths if f[0] > LONG_LINES]
    too_long = [f for f in lengths if f[0] > MAX_LINES]
    for lines, path, head in long_ones:
        print(f"{lines:4d} {path}: {head}")
    print(f"{len(too_long)} over {MAX_LINES} lines (allowed 0), {len(long_ones)} over {LONG_LINES} (allowed {MAX_LONG})")
    return 1 if too_long or len(long_ones) > MAX_LONG else 0


if __name__ == "__main__":
    sys.exit(main())
