#!/usr/bin/env python3
"""app/ holds only the command line (docs/architecture.md, "run"): no source under app/
includes a simulator, renderer, MuJoCo, FCL or OpenCASCADE header; those are reached through
the run library. Lists every include of app/ and exits 1 naming each one that breaks this.

    python3 scripts/app_includes.py ROOT [--list]
"""
import pathlib
import re
import sys

FORBIDDEN = [
    (re.compile(r"^stitchsim/sim/"), "the simulator (sim/)"),
    (re.compile(r"^stitchsim/render/"), "the renderer (render/)"),
    (re.compile(r"^mujoco/"), "MuJoCo"),
    (re.compile(r"^fcl/"), "FCL"),
    # OpenCASCADE's headers: one class per header, named by package prefix.
    (re.compile(r"^(Standard|gp|Geom|Geom2d|GeomAPI|TopoDS|TopExp|TopAbs|BRep\w*|STEP\w*|IGES\w*"
                r"|TColgp|TColStd|NCollection|Interface|XSControl|Precision|ShapeAnalysis"
                r"|BRepBuilderAPI|TopLoc|Poly|Bnd)(_\w*)?\.hxx$"), "OpenCASCADE"),
]
INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]([^>"]+)[>"]')


def main():
    root = pathlib.Path(sys.argv[1])
    listing = "--list" in sys.argv
    bad = 0
    for path in sorted((root / "app").rglob("*")):
        if path.suffix not in {".cpp", ".h", ".in"}:
            continue
        for number, text in enumerate(path.read_text().splitlines(), 1):
            m = INCLUDE.match(text)
            if not m:
                continue
            header = m.group(1)
            where = f"{path.relative_to(root)}:{number}"
            if listing:
                print(f"{where}: {header}")
            for pattern, what in FORBIDDEN:
                if pattern.search(header):
                    print(f"{where}: includes {header}: {what} belongs below the run library")
                    bad += 1
    if bad:
        print(f"app_includes: {bad} include(s) of the layers below run in app/")
        return 1
    print("app_includes: app/ includes no sim, render, MuJoCo, FCL or OpenCASCADE header")
    return 0


if __name__ == "__main__":
    sys.exit(main())
