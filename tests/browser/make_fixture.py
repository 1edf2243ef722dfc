#!/usr/bin/env python3
"""Builds a test HTML report from run/html/report.html with synthetic data.

The page is assembled as `stitchsim verify --html` does it: each marker line of the template is
replaced by an inline script (three.js and OrbitControls from Debian's libjs-three, the data as
JSON with every "</" written "<\\/", run/html/report.js). The data: an 8-joint arm of boxes,
capsules, cylinders and a sphere on a floor rail, a rotator carrying a part body with a curved
panel mesh, stitches in rows on the panel (a few warning and error clusters), the tool path,
poses, findings, one series per rule and two snapshots.

Usage: make_fixture.py OUT.html [--stitches N] [--max-points M] [--max-poses P]
  --stitches N     stitches in the programme (default 20000; 1600000 is wing-sized)
  --max-points M   stitch and path points kept (thinned evenly beyond; default 300000)
  --max-poses P    poses kept (default 50000; finding lines are always kept)
  --broken         write malformed data (for the error-message check)
"""
import argparse
import array
import base64
import json
import math
import os
import struct
import sys
import zlib

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
THREE_DIR = "/usr/share/javascript/three"
MARKERS = {
    "THREE": os.path.join(THREE_DIR, "three.min.js"),
    "ORBIT": os.path.join(THREE_DIR, "examples/js/controls/OrbitControls.js"),
    "APP": os.path.join(ROOT, "run/html/report.js"),
    "AFP": os.path.join(ROOT, "run/html/afp_view.js"),
}
JOINTS = ["rail_x", "a1", "a2", "a3", "a4", "a5", "a6", "rotator"]
HOME = [2.8, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]
PANEL_MM = (1200.0, 800.0)  # part panel size, x and y, mm
ROW_PITCH_MM = 20.0
STITCH_PITCH_MM = 6.0


def b64(typecode, values):
    a = array.array(typecode, values)
    if sys.byteorder != "little":
        a.byteswap()
    return base64.b64encode(a.tobytes()).decode("ascii")


def panel_z_mm(x, y):
    """Height of the curved panel (part frame, mm)."""
    return 60.0 * math.cos(math.pi * x / PANEL_MM[0]) + 0.00005 * y * y


def quat_axis(axis, angle):
    s = math.sin(angle / 2)
    return [math.cos(angle / 2), axis[0] * s, axis[1] * s, axis[2] * s]


def geom(name, kind, size, pos=(0, 0, 0), quat=(1, 0, 0, 0), rgba=(0.75, 0.45, 0.1, 1),
         mesh=None):
    return {"name": name, "type": kind, "size": list(size), "pos": list(pos), "quat": list(quat),
            "rgba": list(rgba), "mesh": mesh}


def body(name, parent, pos, quat=(1, 0, 0, 0), joint=None, geoms=()):
    return {"name": name, "parent": parent, "pos": list(pos), "quat": list(quat),
            "joint": joint, "geoms": list(geoms)}


def hinge(name, axis, index, pos=(0, 0, 0), kind="hinge"):
    return {"name": name, "type": kind, "axis": list(axis), "pos": list(pos), "index": index}


def panel_mesh():
    nx, ny = 40, 24
    verts, faces = [], []
    for j in range(ny + 1):
        for i in range(nx + 1):
            x = (i / nx - 0.5) * PANEL_MM[0]
            y = (j / ny - 0.5) * PANEL_MM[1]
            verts += [x / 1000, y / 1000, (panel_z_mm(x, y) - 4) / 1000]
    for j in range(ny):
        for i in range(nx):
            a = j * (nx + 1) + i
            faces += [a, a + 1, a + nx + 2, a, a + nx + 2, a + nx + 1]
    return {"vertices": b64("f", verts), "faces": b64("I", faces)}


def cell():
    orange, grey, dark = (0.93, 0.45, 0.08, 1), (0.55, 0.57, 0.6, 1), (0.25, 0.27, 0.3, 1)
    y90 = quat_axis((0, 1, 0), math.pi / 2)
    bodies = [
        body("world_static", -1, (0, 0, 0), geoms=[
            geom("floor", "plane", (7, 5, 0.1), (6, 1.5, 0), rgba=(0.82, 0.84, 0.86, 1)),
            geom("rail", "box", (6.25, 0.35, 0.1), (6.25, 0, 0.1), rgba=grey)]),
        body("carriage", -1, (0.7, 0, 0.2), joint=hinge("rail_x", (1, 0, 0), 0, kind="slide"),
             geoms=[geom("carriage", "box", (0.6, 0.5, 0.15), (0, 0, 0.15), rgba=dark)]),
        body("link1", 1, (0, 0, 0.55), quat_axis((0, 0, 1), math.pi / 2),
             joint=hinge("a1", (0, 0, -1), 1),
             geoms=[geom("turret", "cylinder", (0.45, 0.25), (0, 0, 0.05), rgba=orange),
                    geom("shoulder", "box", (0.35, 0.3, 0.3), (0.3, 0, 0.75), rgba=orange)]),
        body("link2", 2, (0.5, 0, 1.045), joint=hinge("a2", (0, 1, 0), 2),
             geoms=[geom("upper_arm", "capsule", (0.17, 0.65), (0, 0, 0.65), rgba=orange)]),
        body("link3", 3, (0, 0, 1.3), joint=hinge("a3", (0, 1, 0), 3),
             geoms=[geom("elbow", "box", (0.25, 0.22, 0.22), (0.05, 0, 0), rgba=orange)]),
        body("link4", 4, (0.3, 0, -0.055), joint=hinge("a4", (-1, 0, 0), 4),
             geoms=[geom("forearm", "capsule", (0.12, 0.55), (0.6, 0, 0), y90, rgba=orange)]),
        body("link5", 5, (1.225, 0, 0), joint=hinge("a5", (0, 1, 0), 5),
             geoms=[geom("wrist", "sphere", (0.13, 0, 0), rgba=grey)]),
        body("flange", 6, (0.29, 0, 0), joint=hinge("a6", (-1, 0, 0), 6),
             geoms=[geom("flange", "cylinder", (0.1, 0.03), (0, 0, 0), y90, rgba=dark),
                    geom("head", "box", (0.3, 0.12, 0.15), (0.35, 0, 0), rgba=(0.2, 0.4, 0.75, 1)),
                    geom("needle", "ellipsoid", (0.06, 0.03, 0.03), (0.68, 0, 0),
                         rgba=(0.85, 0.85, 0.9, 1))]),
        body("rotator", -1, (3.5, 2.6, 0.0), joint=hinge("rotator", (0, 0, 1), 7),
             geoms=[geom("pedestal", "cylinder", (0.5, 0.45), (0, 0, 0.45), rgba=dark)]),
        body("part", 8, (0, 0, 1.0), geoms=[
            geom("part", "mesh", (0, 0, 0), rgba=(0.86, 0.78, 0.6, 1), mesh=0),
            geom("tool_plate", "box", (0.65, 0.45, 0.02), (0, 0, -0.08), rgba=grey)]),
    ]
    return {"joints": JOINTS, "home": HOME, "bodies": bodies, "meshes": [panel_mesh()],
            "part_body": 9}


def stitch_layout(count):
    """Stitch positions (part mm) in rows along x, the programme line of each, the line count."""
    per_row = int(PANEL_MM[0] * 0.9 / STITCH_PITCH_MM)
    rows = max(1, -(-count // per_row))
    row_pitch = min(ROW_PITCH_MM, PANEL_MM[1] * 0.9 / rows)
    pos, lines = array.array("f"), array.array("i")
    line = 10  # header lines before the first stitch
    for k in range(count):
        r, i = divmod(k, per_row)
        if i == 0:
            line += 3  # retract, approach, plunge
        x = -PANEL_MM[0] * 0.45 + i * STITCH_PITCH_MM * (PANEL_MM[0] * 0.9 / per_row /
                                                         STITCH_PITCH_MM)
        x = x if r % 2 == 0 else -x
        y = -PANEL_MM[1] * 0.45 + r * row_pitch
        pos.extend((x, y, panel_z_mm(x, y) + 1.0))
        lines.append(line)
        line += 1
    return pos, lines, line + 5


def verdicts(count):
    """Verdict of each stitch: an error cluster and two warning clusters."""
    v = bytearray(count)
    for lo, hi, mark in ((0.30, 0.31, 1), (0.62, 0.625, 2), (0.63, 0.64, 1)):
        for k in range(int(lo * count), int(hi * count)):
            v[k] = mark
    return v


def thin(count, keep_max, always=()):
    step = max(1, -(-count // keep_max))
    keep = set(range(0, count, step)) | set(always)
    return sorted(k for k in keep if 0 <= k < count)


def findings_for(pos, lines, v, count):
    out = []
    for k in range(count):
        if not v[k] or len(out) >= 400:
            continue
        err = v[k] == 2
        value = 52.5 + (k % 7) if err else 33.0 + (k % 5)
        out.append({"rule": "stitch.side_force" if err else "collision.clearance",
                    "severity": "error" if err else "warning", "line": lines[k], "stitch": k + 1,
                    "value": value if err else 8.0 - (k % 5) * 0.5,
                    "limit": 45.0 if err else 10.0, "unit": "N" if err else "mm",
                    "subject": "needle" if err else "head/part",
                    "message": ("side force over the limit </script> test" if err else
                                "head close to the part"),
                    "position_mm": [pos[3 * k], pos[3 * k + 1], pos[3 * k + 2]]})
    out.sort(key=lambda f: f["line"])
    return out


def series(lines_total, v, lines, buckets=2000):
    bucket_lines = max(1, -(-lines_total // buckets))
    n = -(-lines_total // bucket_lines)
    worst = {}
    for k, mark in enumerate(v):
        if mark:
            b = (lines[k] - 1) // bucket_lines
            worst[b] = max(worst.get(b, 0), mark)
    force_min, force_max, clear_min, clear_max, speed_min, speed_max = ([] for _ in range(6))
    for b in range(n):
        base = 20 + 6 * math.sin(b / 37.0)
        peak = {2: 32, 1: 0}.get(worst.get(b, 0), 0)
        gap = b % 400 < 6  # nothing checked (row changes)
        nan = float("nan")
        force_min.append(nan if gap else base - 4)
        force_max.append(nan if gap else base + 5 + peak)
        c = 40 + 15 * math.cos(b / 53.0) - (33 if worst.get(b) == 1 else 0)
        clear_min.append(c)
        clear_max.append(c + 12)
        s = 30 + 25 * abs(math.sin(b / 90.0))
        speed_min.append(s * 0.2)
        speed_max.append(s)
    common = {"first_line": 1, "bucket_lines": bucket_lines}
    return [
        dict(common, rule="stitch.side_force", subject="needle", unit="N", error_limit=45.0,
             warning_limit=35.0, lower_bound=False, min=b64("f", force_min),
             max=b64("f", force_max)),
        dict(common, rule="collision.clearance", subject="head/part", unit="mm", error_limit=0.0,
             warning_limit=10.0, lower_bound=True, min=b64("f", clear_min),
             max=b64("f", clear_max)),
        dict(common, rule="kin.joint_speed", subject="a1", unit="deg/s", error_limit=80.0,
             warning_limit=None, lower_bound=False, min=b64("f", speed_min),
             max=b64("f", speed_max)),
    ]


def joints_at(line, lines_total):
    """A made-up but plausible pose: the head over the part, sweeping along the rows."""
    f = line / lines_total
    w = 2 * math.pi * f
    return [2.8 + 0.3 * math.sin(w), 0.15 * math.sin(3 * w), 0.42 + 0.05 * math.sin(5 * w),
            0.25 + 0.06 * math.cos(4 * w), 0.2 * math.sin(7 * w), 0.72 + 0.1 * math.sin(2 * w),
            0.8 * math.sin(9 * w), 0.6 * f]


def png(width, height, rgb_at):
    rows = b"".join(b"\x00" + bytes(c for x in range(width) for c in rgb_at(x, y))
                    for y in range(height))

    def chunk(tag, data):
        return (struct.pack(">I", len(data)) + tag + data +
                struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF))
    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(rows)) +
            chunk(b"IEND", b""))


def snapshots():
    shots = []
    for name, tint in (("overview.png", (40, 90, 160)), ("line_0001234_side_force.png",
                                                         (170, 40, 40))):
        data = png(160, 120, lambda x, y, t=tint: (t[0] + x // 2, t[1] + y // 2, t[2]))
        shots.append({"name": name, "png": base64.b64encode(data).decode("ascii")})
    return shots


def make_data(count, max_points, max_poses):
    pos, lines, lines_total = stitch_layout(count)
    v = verdicts(count)
    findings = findings_for(pos, lines, v, count)
    kept = thin(count, max_points)
    pose_lines = sorted(set(range(1, lines_total + 1, max(1, -(-lines_total // max_poses)))) |
                        {f["line"] for f in findings})
    pose_q, pose_t = [], []
    for line in pose_lines:
        pose_q += joints_at(line, lines_total)
        pose_t.append(line * 0.9)
    errors = sum(1 for f in findings if f["severity"] == "error")
    rules = [
        {"id": "stitch.side_force", "description": "needle side force", "unit": "N",
         "checked": count, "errors": errors, "warnings": 0, "error_limit": 45.0,
         "warning_limit": 35.0, "worst_value": 58.5, "worst_line": findings[0]["line"] if
         findings else 0, "worst_stitch": 1, "truncated": False},
        {"id": "collision.clearance", "description": "head to part clearance", "unit": "mm",
         "checked": lines_total, "errors": 0, "warnings": len(findings) - errors,
         "error_limit": 0.0, "warning_limit": 10.0, "worst_value": 6.0, "worst_line": 0,
         "worst_stitch": -1, "truncated": len(findings) >= 400},
        {"id": "kin.joint_speed", "description": "joint speeds", "unit": "deg/s",
         "checked": lines_total, "errors": 0, "warnings": 0, "error_limit": 80.0,
         "warning_limit": None, "worst_value": None, "worst_line": 0, "worst_stitch": -1,
         "truncated": False},
    ]
    return {
        "format": "stitchsim-html-1",
        "summary": {"program": "fixture.nc", "scene_file": "scenes/fixture.yaml",
                    "scene": "fixture panel", "head": "RS535", "verdict": "fail" if findings
                    else "pass", "lines": lines_total, "moves": lines_total - count,
                    "stitches": count, "cycle_time_s": lines_total * 0.9,
                    "cycle_time_timed_s": lines_total * 0.85, "errors": errors,
                    "warnings": len(findings) - errors, "tool_version": "fixture",
                    "kind": "stitch"},
        "rules": rules,
        "skipped": [{"id": "afp.coverage", "reason": "not an AFP scene"}],
        "findings": findings,
        "snapshots": snapshots(),
        "cell": cell(),
        "stitches": {"positions": b64("f", (pos[3 * k + c] for k in kept for c in range(3))),
                     "verdict": base64.b64encode(bytes(v[k] for k in kept)).decode("ascii"),
                     "lines": b64("i", (lines[k] for k in kept)), "total": count},
        "path": {"positions": b64("f", (pos[3 * k + c] + (c == 2) * 2.0 for k in kept
                                        for c in range(3))),
                 "lines": b64("i", (lines[k] for k in kept))},
        "drawings": [{"label": "constraint", "rgba": [0.4, 0.2, 0.7, 1], "positions": b64(
            "f", (c for i in range(200) for c in (-560 + 5.6 * i, -380.0,
                                                  panel_z_mm(-560 + 5.6 * i, -380) + 1)))}],
        "poses": {"lines": b64("i", pose_lines), "q": b64("f", pose_q), "t": b64("f", pose_t)},
        "series": series(lines_total, v, lines),
    }


def assemble(template, data_json):
    out = []
    for line in template.split("\n"):
        key = line.strip()
        if key.startswith("<!--STITCHSIM:") and key.endswith("-->"):
            name = key[len("<!--STITCHSIM:"):-3]
            if name == "DATA":
                out.append('<script id="stitchsim-data" type="application/json">' +
                           data_json.replace("</", "<\\/") + "</script>")
            else:
                with open(MARKERS[name], encoding="utf-8") as f:
                    out.append("<script>" + f.read() + "</script>")
        else:
            out.append(line)
    return "\n".join(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out")
    ap.add_argument("--stitches", type=int, default=20000)
    ap.add_argument("--max-points", type=int, default=300000)
    ap.add_argument("--max-poses", type=int, default=50000)
    ap.add_argument("--broken", action="store_true")
    args = ap.parse_args()
    data = make_data(args.stitches, args.max_points, args.max_poses)
    if args.broken:
        data["stitches"]["verdict"] = "!!not base64!!"
    with open(os.path.join(ROOT, "run/html/report.html"), encoding="utf-8") as f:
        template = f.read()
    page = assemble(template, json.dumps(data, separators=(",", ":"), allow_nan=False))
    with open(args.out, "w", encoding="utf-8") as f:
        f.write(page)
    print(f"{args.out}: {os.path.getsize(args.out) / 1e6:.1f} MB, {args.stitches} stitches")


if __name__ == "__main__":
    main()
