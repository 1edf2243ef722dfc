#!/usr/bin/env bash
# Seed 004's planar 45 deg case (bench/seed004_cases.txt, planar_45) through `sequence --html`
# and its page checked in headless Chromium (check_sequence.mjs):
#   tests/browser/run_sequence.sh STITCHSIM [OUT_DIR]
# The plies are planned, laid zig-zag (bench/seed004_figures.py's bad order) with --order, then
# reordered bidirectionally by tool distance with --html and --report. OUT_DIR keeps the files
# and screenshots (default: a scratch folder, removed).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
bin="$1" out="${2:-}"
if [[ -z "$out" ]]; then
  out="$(mktemp -d "/tmp/stitchsim-sequence-$$-XXXX")"
  trap 'rm -rf "$out"' EXIT
fi
mkdir -p "$out"
scene="$root/scenes/seq_plate.yaml"
"$bin" plan ply --scene "$scene" --ply base_45 --ply pad_45_left --ply pad_45_right \
  --ply pad_45_mid --quiet -o "$out/planned.nc" >/dev/null
PYTHONPATH="$root/bench" python3 -c '
import json, sys, seed004_figures as f
json.dump(f.bad_order(f.programme_courses(sys.argv[1]), "zigzag"), open(sys.argv[2], "w"))
' "$out/planned.nc" "$out/bad_order.json"
"$bin" sequence "$out/planned.nc" --scene "$scene" --order "$out/bad_order.json" --quiet \
  -o "$out/bad.nc" >/dev/null
"$bin" sequence "$out/bad.nc" --scene "$scene" --bidirectional --cost tool --quiet \
  -o "$out/seq.nc" --report "$out/seq.json" --html "$out/seq.html" >/dev/null
node "$here/check_sequence.mjs" "$out/seq.html" "$out/seq.json" --out "$out"
