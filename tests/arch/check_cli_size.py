#!/usr/bin/env python3
"""Fails when src/cli has more than LIMIT lines (the command line stays thin).

The command line only parses options and calls the library (docs/architecture.md); logic and
rendering belong to the library modules. Counts every file of src/cli as `wc -l src/cli/*` does
(newline characters of .cpp and .hpp files alike).
usage: check_cli_size.py SOURCE_DIR [LIMIT]   (LIMIT: default 1500)
"""
import os
import sys


def main(root, limit):
    cli = os.path.join(root, "src", "cli")
    counts = {}
    for name in sorted(os.listdir(cli)):
        path = os.path.join(cli, name)
        if os.path.isfile(path):
            with open(path, "rb") as f:
                counts[name] = f.read().count(b"\n")
    total = sum(counts.values())
    if total > limit:
        largest = sorted(counts.items(), key=lambda kv: -kv[1])[:5]
        print(f"src/cli has {total} lines, more than {limit}: move logic and rendering into the "
              f"library (docs/architecture.md). Largest: "
              + ", ".join(f"{n} {c}" for n, c in largest))
        return 1
    print(f"src/cli: {total} lines in {len(counts)} files (limit {limit})")
    return 0


if __name__ == "__main__":
    if len(sys.argv) not in (2, 3):
        print(__doc__)
        sys.exit(64)
    sys.exit(main(sys.argv[1], int(sys.argv[2]) if len(sys.argv) == 3 else 1500))
