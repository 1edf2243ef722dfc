#!/usr/bin/env python3
"""TSPLIB symmetric instances as AFP programmes through `stitchsim sequence` (issue 28's first
paragraph; docs/sequence.md).

  tsplib_programmes.py BIN OUT [--only NAME,...] [--time-limit S] [--bidirectional]

For each symmetric instance of bench/data/tsplib/optima.txt (EUC_2D): the cities, scaled by one
factor s into scenes/seq_plate.yaml's base ply (960 x 560 mm about the plate's centre), become
one ply of 2 mm courses, one per city, centred on the city and laid along +x (the programme
lists them in the file's order, all forwards). `sequence PROG --scene seq_plate --cost tool
--home <city 1, on the surface> --return-home --report r.json` orders them. Printed per
instance, all in mm on the plate unless said:
  O      the published optimum (TSPLIB's integer distances) times s;
  C      the solver's cost: the tool-point moves, from the end of one course to the start of
         the next (the report's totals.offpart_after.tool_mm), home first and last;
  E      the Euclidean length, times s, of the closed city tour in the solver's order
         (home = city 1, unrounded distances);
  C - E  what the 2 mm courses add: each move starts 1 mm past its city and ends 1 mm before
         the next, so it differs from the city-to-city distance by at most 2 mm (home: 1 mm);
         recomputed here move by move and checked against C;
  T      the order's tour length in TSPLIB's own rounded distances (unscaled), and its exact
         gap to the published optimum, (T - optimum) / optimum;
  flown  the regenerated off-part path, with its lifts (totals.flown_tool_mm.offpart_after).
The solver minimises C, not T: C's optimum differs from O by the course offsets (up to 2 mm a
move) and TSPLIB's rounding (up to 0.5 s a move), so a gap in T near 0 is the honest measure.
"""
import argparse
import json
import math
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
DATA = os.path.join(HERE, "data", "tsplib")
SCENE = os.path.join(ROOT, "scenes", "seq_plate.yaml")
PLY = "base_0"  # seq_plate's 1000 x 600 mm base ply at 0 deg
HALF_X, HALF_Y = 480.0, 280.0  # the cities fit in +-HALF about the plate's centre, mm
COURSE = 2.0  # course length, mm
POSE = "A0 B0 C-90"  # travel along +x, head axis up (bench/make_sequence_bench.py)


def read_optima():
    out = []
    with open(os.path.join(DATA, "optima.txt")) as f:
        for line in f:
            parts = line.split("#", 1)[0].split()
            if len(parts) == 3:
                out.append((parts[0], parts[1] == "TSP", float(parts[2])))
    return out


def read_coords(path):
    """NODE_COORD_SECTION of an EUC_2D file, in node order."""
    coords, section, kind = [], False, None
    with open(path) as f:
        for line in f:
            line = line.strip()
            if line.startswith("EDGE_WEIGHT_TYPE"):
                kind = line.split(":", 1)[1].strip()
            elif line == "NODE_COORD_SECTION":
                section = True
            elif line == "EOF":
                break
            elif section and line:
                i, x, y = line.split()[:3]
                assert int(i) == len(coords) + 1, path
                coords.append((float(x), float(y)))
    if kind != "EUC_2D":
        sys.exit("%s: EDGE_WEIGHT_TYPE %s, not EUC_2D" % (path, kind))
    return coords


def nint_dist(a, b):
    return math.floor(math.hypot(a[0] - b[0], a[1] - b[1]) + 0.5)


def place(coords):
    """Scale s and the cities' centres on the plate (mm)."""
    xs, ys = [c[0] for c in coords], [c[1] for c in coords]
    cx, cy = (min(xs) + max(xs)) / 2, (min(ys) + max(ys)) / 2
    s = min(2 * HALF_X / max(max(xs) - min(xs), 1e-9), 2 * HALF_Y / max(max(ys) - min(ys), 1e-9))
    return s, [((x - cx) * s, (y - cy) * s) for x, y in coords]


def write_programme(path, centres, name):
    with open(path, "w") as f:
        w = lambda s: f.write(s + "\n")
        w("%")
        w("(STITCHSIM scene=seq_plate head=afp)")
        w("(TSPLIB %s: one %g mm course per city, bench/tsplib_programmes.py)" % (name, COURSE))
        w("G21 G90")
        w("T3 M6")
        w("M70 P1 (PLY name=%s)" % PLY)
        for k, (x, y) in enumerate(centres):
            x0, x1 = x - COURSE / 2, x + COURSE / 2
            w("M71 P%d (COURSE %d)" % (k + 1, k + 1))
            w("G0 X%.4f Y%.4f Z100 %s M20" % (x0, y, POSE))
            w("M21")
            w("G1 X%.4f Y%.4f Z0 F12000" % (x0, y))
            w("M62 P8")
            w("G1 X%.4f Y%.4f Z0" % (x1, y))
            w("M63 P0")
            w("M20")
            w("G0 X%.4f Y%.4f Z100" % (x1, y))
            w("M72")
        w("M30")
        w("%")


def course_ends(centre, reversed_):
    (x, y), h = centre, COURSE / 2
    start, end = (x - h, y), (x + h, y)
    return (end, start) if reversed_ else (start, end)


def measure(order, centres, coords, home):
    """C recomputed (tool-point moves), E (scaled Euclidean city tour), T (TSPLIB tour)."""
    c = e = 0.0
    here_pt, here_city = home, 0
    for k, rev in order:
        start, end = course_ends(centres[k], rev)
        c += math.dist(here_pt, start)
        e += math.dist(centres[here_city], centres[k])
        here_pt, here_city = end, k
    c += math.dist(here_pt, home)
    e += math.dist(centres[here_city], centres[0])
    cities = [0] + [k for k, _ in order]
    t = sum(nint_dist(coords[cities[i]], coords[cities[(i + 1) % len(cities)]])
            for i in range(len(cities)))
    return c, e, t


def run_instance(a, name, optimum):
    coords = read_coords(os.path.join(DATA, name + ".tsp"))
    s, centres = place(coords)
    prog = os.path.join(a.out, name + ".nc")
    report = os.path.join(a.out, name + ".json")
    write_programme(prog, centres, name)
    home = centres[0]
    cmd = [a.bin, "sequence", prog, "--scene", SCENE, "--cost", "tool", "--return-home",
           "--home", "%.4f,%.4f,0,0,0,-90" % home, "--report", report,
           "-o", os.path.join(a.out, name + "_seq.nc")]
    if a.time_limit is not None:
        cmd += ["--time-limit", str(a.time_limit)]
    if a.bidirectional:
        cmd.append("--bidirectional")
    t0 = time.time()
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    wall = time.time() - t0
    if p.returncode != 0:
        sys.exit("failed (%d): %s\n%s%s" % (p.returncode, " ".join(cmd), p.stdout, p.stderr))
    with open(report) as f:
        r = json.load(f)
    order = [(v["course"] - 1, v["reversed"]) for v in r["order"]]
    assert sorted(k for k, _ in order) == list(range(len(coords))), name
    c_report = r["totals"]["offpart_after"]["tool_mm"]
    flown = r["totals"]["flown_tool_mm"]["offpart_after"]
    c, e, t = measure(order, centres, coords, home)
    if abs(c - c_report) > 1e-6 * max(1.0, c):
        sys.exit("%s: the report's tool cost %.6f is not the moves' sum %.6f" % (name, c_report, c))
    bound = 2.0 * len(coords)  # each move changes by at most 2 mm (home legs: 1 mm)
    assert abs(c - e) <= bound + 1e-6, name
    status = ",".join(sorted({st.get("status", "?") for st in r["sets"]}))
    print("| %s | %d | %.4f | %.1f | %.1f | %.1f | %+.1f | %.0f | %+.3f | %.1f | %.1f | %s |" % (
        name, len(coords), s, optimum * s, c, e, c - e, t, 100.0 * (t - optimum) / optimum,
        flown, wall, status))
    sys.stdout.flush()
    return 100.0 * (t - optimum) / optimum


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("bin", help="the stitchsim executable")
    ap.add_argument("out", help="folder for the programmes and reports")
    ap.add_argument("--only", help="instance names, comma-separated")
    ap.add_argument("--time-limit", type=float, help="sequence's --time-limit, s")
    ap.add_argument("--bidirectional", action="store_true")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    only = set(a.only.split(",")) if a.only else None
    print("| instance | n | s | O mm | C mm | E mm | C - E mm | T | gap of T % | flown mm | "
          "wall s | stop |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    gaps = [run_instance(a, name, opt) for name, symmetric, opt in read_optima()
            if symmetric and (only is None or name in only)]
    if gaps:
        print("\nT's gap to the published optimum: worst %+.3f %%, mean %+.3f %% over %d" % (
            max(gaps), sum(gaps) / len(gaps), len(gaps)))


if __name__ == "__main__":
    main()
