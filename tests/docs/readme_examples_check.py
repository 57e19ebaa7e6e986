#!/usr/bin/python3
"""The README prints example files in full: each `<!-- example: PATH -->` line is followed by a
fenced code block that must equal the file PATH (relative to the repository root) byte for byte,
so what CI builds and runs (examples/consumer, examples/python/tour.py) is what the README shows.

usage: readme_examples_check.py REPO_ROOT [PATH ...]   (the PATHs that must be printed)
"""
import re
import sys
from pathlib import Path


def main():
    root = Path(sys.argv[1])
    required = set(sys.argv[2:])
    text = (root / "README.md").read_text()
    pattern = re.compile(r"^<!-- example: (\S+) -->\n```[a-z]*\n(.*?)^```$", re.M | re.S)
    found = {}
    for m in pattern.finditer(text):
        line = text.count("\n", 0, m.start()) + 1
        found[m.group(1)] = (line, m.group(2))
    problems = []
    for path in sorted(required - found.keys()):
        problems.append(f"README.md: no block for {path} (a line <!-- example: {path} --> before a fenced block)")
    for path, (line, block) in sorted(found.items()):
        file = root / path
        if not file.is_file():
            problems.append(f"README.md:{line}: {path} does not exist")
        elif file.read_text() != block:
            a, b = block.splitlines(), file.read_text().splitlines()
            k = next((i for i, (x, y) in enumerate(zip(a, b)) if x != y), min(len(a), len(b)))
            problems.append(f"README.md:{line + 2 + k}: the block differs from {path} at its line {k + 1}")
    for p in problems:
        print(p)
    print(f"{len(found)} example blocks, {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
