#!/usr/bin/env python3
"""Fails when a header or source of an upstream module includes a downstream one.

The modules, upstream first (docs/architecture.md): a file of module M may include feint headers of
M and of the modules before it, never of one after it. feint/error.hpp and feint/rng.hpp belong to
base. Files: include/feint/<module>/** and src/<module>/** (src/cli may include everything).
usage: check_includes.py SOURCE_DIR
"""
import os
import re
import sys

ORDER = ["base", "io", "metrics", "stats", "models", "sim", "tables", "analysis", "plot",
         "publish", "collect", "commands", "cli"]
RANK = {m: i for i, m in enumerate(ORDER)}
INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]feint/([^">]+)[">]', re.M)


def module_of_header(path):
    """feint/io/csv.hpp -> io; feint/error.hpp -> base."""
    parts = path.split("/")
    return parts[0] if len(parts) > 1 else "base"


def main(root):
    failures, checked = [], 0
    for top, owner_of in (("include/feint", lambda rel: rel.split(os.sep)[0] if os.sep in rel else "base"),
                          ("src", lambda rel: rel.split(os.sep)[0])):
        base = os.path.join(root, top)
        for dirpath, _, files in os.walk(base):
            for name in files:
                if not name.endswith((".hpp", ".cpp", ".h")):
                    continue
                path = os.path.join(dirpath, name)
                rel = os.path.relpath(path, base)
                owner = owner_of(rel)
                if owner not in RANK:
                    failures.append(f"{top}/{rel}: module '{owner}' is not in the module order "
                                    f"of tests/arch/check_includes.py (add it)")
                    continue
                checked += 1
                with open(path, encoding="utf-8") as f:
                    text = f.read()
                for m in INCLUDE.finditer(text):
                    target = module_of_header(m.group(1))
                    if target not in RANK:
                        failures.append(f"{top}/{rel}: includes feint/{m.group(1)} of unknown module")
                    elif RANK[target] > RANK[owner]:
                        line = text.count("\n", 0, m.start()) + 1
                        failures.append(f"{top}/{rel}:{line}: {owner} includes feint/{m.group(1)} "
                                        f"of {target}, which is downstream of it")
    for f in failures:
        print("FAIL:", f)
    print(f"{checked} files checked against the order {' -> '.join(ORDER)}: "
          f"{len(failures)} problem(s)")
    return 1 if failures or checked == 0 else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "."))
