#!/usr/bin/env python3
"""Fails when a function of src/ or include/ is longer than LIMIT lines without a reason beside it.

A function past about 80 lines is usually two ideas (docs/architecture.md). One that stays longer
says why in a comment that starts with "Long:" on one of the five lines above its first line, e.g.
  // Long: one pass over the rows; its counters are the function's state.
A function is a definition at namespace or class indentation (0 or 2 spaces), its signature on
one or more lines ending in '{' after the closing parenthesis, up to the '}' at the same
indentation (the project's clang-format style).
usage: check_function_length.py SOURCE_DIR [LIMIT]   (LIMIT: default 80)
"""
import os
import re
import sys

# A definition starts at namespace or class indentation (0 or 2 spaces) with a name, and its body
# opens with a '{' that ends a line after the closing parenthesis of its parameters; the signature may
# span several lines (parameters aligned below the first).
HEAD = re.compile(r'^( {0,2})[A-Za-z_~][^;{}]*\(')
NOT_A_FUNCTION = re.compile(r'^\s*(if|for|while|switch|namespace|struct|class|else|do|catch|return|using|template|typedef|enum|union)\b')
OPENS_BODY = re.compile(r'\)\s*(const)?\s*(noexcept)?\s*(override)?\s*(->\s*[^{]+)?(:[^;]*)?\{\s*$')


def long_functions(path, limit):
    with open(path, encoding="utf-8", errors="replace") as f:
        lines = f.read().split("\n")
    found, i = [], 0
    while i < len(lines):
        m = HEAD.match(lines[i])
        if m and not NOT_A_FUNCTION.match(lines[i]) and not lines[i].lstrip().startswith("//"):
            # the signature: this line and the following ones up to the first ending in '{' or ';'
            k = i
            while k < len(lines) and k < i + 8 and not lines[k].rstrip().endswith(("{", ";", "}")):
                k += 1
            if k < len(lines) and OPENS_BODY.search(lines[k]) and "=" not in lines[i].split("(")[0]:
                end = re.compile("^" + m.group(1) + r"\}")
                j = k + 1
                while j < len(lines) and not end.match(lines[j]):
                    j += 1
                length = j - i + 1
                above = lines[max(0, i - 5):i]
                reasoned = any(re.match(r"^\s*//\s*Long:", a) for a in above)
                if length > limit and not reasoned:
                    found.append((i + 1, length, lines[i].strip()[:100]))
                i = j
        i += 1
    return found


def main(root, limit):
    problems, checked = [], 0
    for top in ("src", "include"):
        for dirpath, _, files in os.walk(os.path.join(root, top)):
            for name in sorted(files):
                if name.endswith((".cpp", ".hpp")):
                    path = os.path.join(dirpath, name)
                    checked += 1
                    for line, length, text in long_functions(path, limit):
                        problems.append(f"{os.path.relpath(path, root)}:{line}: {length} lines: {text}")
    for p in problems:
        print("FAIL:", p)
    print(f"{checked} files checked: {len(problems)} function(s) over {limit} lines without a "
          f"'// Long:' reason (split them, or say why beside them)")
    return 1 if problems or checked == 0 else 0


if __name__ == "__main__":
    if len(sys.argv) not in (2, 3):
        print(__doc__)
        sys.exit(64)
    sys.exit(main(sys.argv[1], int(sys.argv[2]) if len(sys.argv) == 3 else 80))
