#!/usr/bin/env python3
"""No literal pi outside common/units.h (issue 27).

Pi and its usual multiples written out in our own C++ (`M_PI`, `3.14159...`, `6.28318...`,
`1.5707963...`, `0.0174532925...`, `57.29577...`, `std::numbers::pi`, `acos(-1)`) instead of
`kPi`, `kDeg`, `kRadToDeg` from common/include/stitchsim/common/units.h, the one place that
spells it. Comments and string literals are not code and are skipped (a URDF text in a test
may say rpy="0 0 1.5707963267948966"). Run from anywhere:
`python3 scripts/literal_pi.py [ROOT]`; prints every hit as `file:line: text` and exits 1 if
there is one (ctest: `literal_pi`).
"""
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from size_bounds import EXTENSIONS, FOLDERS, blank_literals  # noqa: E402

UNITS_H = os.path.join("common", "include", "stitchsim", "common", "units.h")
LITERAL_PI = re.compile(
    r"\bM_PI\w*|\b3\.14159|\b6\.28318|\b1\.5707963|\b0\.0174532|\b57\.29577"
    r"|\bnumbers::(inv_)?pi(_v)?\b|\bacos[fl]?\s*\(\s*-\s*1(\.0*)?[fFlL]?\s*\)")


def hits(text):
    """(line, code line) of every literal pi in `text`, comments and strings skipped."""
    code = blank_literals(text).split("\n")
    lines = text.split("\n")
    return [(k + 1, lines[k].strip()) for k, line in enumerate(code) if LITERAL_PI.search(line)]


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else
                           os.path.join(os.path.dirname(__file__), ".."))
    problems = []
    for folder in sorted(set(FOLDERS) | {"run"}):
        for dirpath, _, files in os.walk(os.path.join(root, folder)):
            for name in sorted(files):
                path = os.path.join(dirpath, name)
                rel = os.path.relpath(path, root)
                if not name.endswith(EXTENSIONS) or rel == UNITS_H:
                    continue
                with open(path, encoding="utf-8", errors="replace") as f:
                    problems += [(rel, n, line) for n, line in hits(f.read())]
    for rel, n, line in sorted(problems):
        print(f"{rel}:{n}: {line}")
    if problems:
        print(f"literal_pi: {len(problems)} literal pi outside {UNITS_H}: use kPi, kDeg, "
              "kRadToDeg")
        return 1
    print(f"literal_pi: no literal pi outside {UNITS_H}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
