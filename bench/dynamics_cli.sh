#!/usr/bin/env bash
# Timed CLI runs for issue 14 (S10, done-when 5): the wing (jump raster, 1.66 M stitches, every
# rule with collision) verified in kinematic mode on the MuJoCo model against a baseline binary
# of the release before it (no MuJoCo in the loop, no timed trajectory), alternating, RUNS
# times each; and the dynamic mode's real-time factor on the decoupled 8 in circle.
#   bash bench/dynamics_cli.sh BIN BASELINE_BIN [RUNS]
# BASELINE_BIN: e.g. a build of the previous release (git worktree add ../base <commit>).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
bin=${1:?BIN}
base=${2:?BASELINE_BIN}
runs=${3:-3}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
scenes=$here/../scenes
"$bin" plan raster --scene "$scenes/wing_cover.yaml" --strategy jump -o "$out/wing.nc" >/dev/null
for ((r = 1; r <= runs; r++)); do
  /usr/bin/time -f "wing baseline  %e s wall %U s user %M KB peak" "$base" verify "$out/wing.nc" \
    --scene "$scenes/wing_cover.yaml" --report "$out/base.json" >/dev/null || true
  /usr/bin/time -f "wing kinematic %e s wall %U s user %M KB peak" "$bin" verify "$out/wing.nc" \
    --scene "$scenes/wing_cover.yaml" --report "$out/new.json" >/dev/null || true
done
python3 - "$out/base.json" "$out/new.json" <<'PY'
import json, sys
b, n = (json.load(open(p)) for p in sys.argv[1:3])
print("  verdicts: baseline %s (%d errors), kinematic %s (%d errors)" % (b["verdict"], b["counts"]["errors"], n["verdict"], n["counts"]["errors"]))
print("  cycle time: %.1f s at the programmed speeds, %.1f s with acceleration" % (n["cycle_time_s"], n["cycle_time_timed_s"]))
PY
"$bin" plan stitch --scene "$scenes/circle_8in.yaml" --path circle --mode decoupled \
  -o "$out/circle.nc" >/dev/null
for ((r = 1; r <= runs; r++)); do
  "$bin" verify "$out/circle.nc" --scene "$scenes/circle_8in.yaml" --dynamics 2>&1 >/dev/null |
    grep '^dynamics:' || true
done
