#!/usr/bin/env python3
"""Seed 004's test cases beside the paper's figures (issue 13; docs/sequence.md, "Measured").

For every case of bench/seed004_cases.txt (`name scene ply,ply,... [zigzag|as-planned]`):
  1. `plan ply` writes the case's plies into one programme (the plies in the listed order);
  2. the programme is deliberately badly ordered: within each ply the courses are laid
     zig-zag across it (1, N, 2, N-1, ...) unless the case says as-planned, all forwards;
     `sequence --order` writes it, so that it has the same kind of off-part moves as the
     reordered ones (a fair comparison);
  3. `sequence --bidirectional` reorders it with the seed's method and with ours, both with
     `--measure-gap` (every set of up to 16 courses also solved exactly);
  4. `verify` (collision on) runs on the badly ordered programme and on both results.
Prints one table (flown tool path: total and off-part reductions, as the seed reports them)
and the per-set gaps to the optimum, and writes OUT/figures.json.

usage: seed004_figures.py BIN OUT [--cases FILE] [--no-verify] [--only NAME]
"""
import argparse
import json
import os
import re
import subprocess
import sys
import time

# (cost, solver): the seed reports the tool point's distance; our default cost is the axes'.
RUNS = (("tool", "seed"), ("tool", "local"), ("axes", "seed"), ("axes", "local"))
HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)

# Seed 004, section 4.5 (total / off-part reduction, %).
PAPER = {
    "planar_0": (38.1, 67.9),
    "planar_0_equi": (36.7, 65.0),
    "planar_45": (35.6, 57.5),
    "planar_90": (34.9, 56.2),
    "cyl_single": (44.6, 83.5),
    "cyl_two": (45.1, 83.3),
    "cyl_padups": (None, None),
}


def run(cmd, check=True):
    t0 = time.time()
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if check and p.returncode != 0:
        sys.exit("failed (%d): %s\n%s%s" % (p.returncode, " ".join(cmd), p.stdout, p.stderr))
    return p, time.time() - t0


def read_cases(path):
    cases = []
    with open(path) as f:
        for line in f:
            line = line.split("#", 1)[0].strip()
            if not line:
                continue
            parts = line.split()
            style = parts[3] if len(parts) > 3 else "zigzag"
            cases.append((parts[0], parts[1], parts[2].split(","), style))
    return cases


def programme_courses(nc):
    """(ply, course) in programme order, from the M70 / M71 marks."""
    out, ply = [], 0
    with open(nc) as f:
        for line in f:
            m = re.search(r"\bM70 P(\d+)", line)
            if m:
                ply = int(m.group(1))
            m = re.search(r"\bM71 P(\d+)", line)
            if m:
                out.append((ply, int(m.group(1))))
    return out


def bad_order(courses, style):
    by_ply = []
    for ply, course in courses:
        if not by_ply or by_ply[-1][0] != ply:
            by_ply.append((ply, []))
        by_ply[-1][1].append(course)
    order = []
    for ply, cs in by_ply:
        if style == "zigzag":
            lo, hi, zz = 0, len(cs) - 1, []
            while lo <= hi:
                zz.append(cs[lo])
                if hi != lo:
                    zz.append(cs[hi])
                lo, hi = lo + 1, hi - 1
            cs = zz
        order += [{"ply": ply, "course": c, "reversed": False} for c in cs]
    return {"order": order}


def reduction(before, after):
    return 100.0 * (before - after) / before if before > 0 else 0.0


def one_case(binary, out, name, scene, plies, style, verify):
    d = os.path.join(out, name)
    os.makedirs(d, exist_ok=True)
    scene = os.path.join(ROOT, scene) if not os.path.isabs(scene) else scene
    planned = os.path.join(d, "planned.nc")
    cmd = [binary, "plan", "ply", "--scene", scene, "-o", planned]
    for p in plies:
        cmd += ["--ply", p]
    _, t_plan = run(cmd)
    with open(os.path.join(d, "bad_order.json"), "w") as f:
        json.dump(bad_order(programme_courses(planned), style), f)
    bad = os.path.join(d, "bad.nc")
    run([binary, "sequence", planned, "--scene", scene, "-o", bad, "--order",
         os.path.join(d, "bad_order.json")])
    row = {"case": name, "scene": scene, "plies": plies, "bad_order": style,
           "plan_s": t_plan, "courses": len(programme_courses(planned))}
    if verify:
        p, t = run([binary, "verify", bad, "--scene", scene], check=False)
        row["verify_bad"] = p.returncode
    for cost, solver in RUNS:
        key = cost + "_" + solver
        nc, rep = os.path.join(d, key + ".nc"), os.path.join(d, key + ".json")
        _, t = run([binary, "sequence", bad, "--scene", scene, "--bidirectional", "--solver",
                    solver, "--cost", cost, "--measure-gap", "-o", nc, "--report", rep])
        with open(rep) as f:
            r = json.load(f)
        fl = r["totals"]["flown_tool_mm"]
        row[key] = {
            "seconds": t,
            "total_pct": reduction(fl["total_before"], fl["total_after"]),
            "offpart_pct": reduction(fl["offpart_before"], fl["offpart_after"]),
            "axes_offpart_pct": reduction(r["totals"]["offpart_before"]["axes"],
                                          r["totals"]["offpart_after"]["axes"]),
            "sets": [{"plies": s["plies"], "courses": s["courses"], "cost": s["cost"],
                      "optimum": s["optimum"],
                      "gap_pct": None if s["optimum"] is None else 100 * s["gap"]}
                     for s in r["sets"]],
        }
        if verify:
            p, _ = run([binary, "verify", nc, "--scene", scene], check=False)
            row[key]["verify"] = p.returncode
    return row


def fmt(v):
    return "  -  " if v is None else "%5.1f" % v


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("binary")
    ap.add_argument("out")
    ap.add_argument("--cases", default=os.path.join(HERE, "seed004_cases.txt"))
    ap.add_argument("--no-verify", action="store_true")
    ap.add_argument("--only")
    a = ap.parse_args()
    rows = []
    for name, scene, plies, style in read_cases(a.cases):
        if a.only and name != a.only:
            continue
        rows.append(one_case(a.binary, a.out, name, scene, plies, style, not a.no_verify))
    for cost in ("tool", "axes"):
        print("\n--cost %s: flown tool path reduction, %% total / off-part: paper | seed's method | "
              "ours; verify exit of bad / seed / ours" % cost)
        for r in rows:
            pt, po = PAPER.get(r["case"], (None, None))
            s, o = r[cost + "_seed"], r[cost + "_local"]
            print("%-14s %3d courses | %s / %s | %s / %s | %s / %s | %s/%s/%s" % (
                r["case"], r["courses"], fmt(pt), fmt(po), fmt(s["total_pct"]),
                fmt(s["offpart_pct"]), fmt(o["total_pct"]), fmt(o["offpart_pct"]),
                r.get("verify_bad", "-"), s.get("verify", "-"), o.get("verify", "-")))
        print("  per set, %s cost: gap to the exact optimum, %%" % cost)
        for r in rows:
            for k, (ss, so) in enumerate(zip(r[cost + "_seed"]["sets"], r[cost + "_local"]["sets"])):
                print("  %-14s set %d plies %-10s %3d courses: seed %s  ours %s" % (
                    r["case"], k + 1, ",".join(map(str, so["plies"])), so["courses"],
                    "n/a" if ss["gap_pct"] is None else "%.3f" % ss["gap_pct"],
                    "n/a" if so["gap_pct"] is None else "%.3f" % so["gap_pct"]))
    with open(os.path.join(a.out, "figures.json"), "w") as f:
        json.dump(rows, f, indent=1)


if __name__ == "__main__":
    main()
