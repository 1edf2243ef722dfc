#!/usr/bin/env bash
# The wing's plies ordered by the timed measure (issue 28, done-when 4): each ply of
# scenes/naca_wing.yaml planned by `plan ply`, sequenced with `--cost timed --bidirectional`,
# the result verified (`verify` exit 0 wanted); per ply the off-part cost before and after in
# every measure, and the wall times of planning, sequencing and verifying.
#   bash bench/sequence_wing_timed.sh [BIN] [PLY ...]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
bin=${1:-$here/../build/app/stitchsim}
shift || true
scene=$here/../scenes/naca_wing.yaml
plies=("$@")
[[ ${#plies[@]} -gt 0 ]] || plies=(upper_0 upper_45 upper_skin_0)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
status=0
for ply in "${plies[@]}"; do
  /usr/bin/time -f "$ply plan     %e s wall %M KB peak" "$bin" plan ply --scene "$scene" \
    --ply "$ply" -o "$out/$ply.nc" >/dev/null
  /usr/bin/time -f "$ply sequence %e s wall %M KB peak" "$bin" sequence "$out/$ply.nc" \
    --scene "$scene" --cost timed --bidirectional --quiet -o "$out/${ply}_seq.nc" \
    --report "$out/$ply.json" >/dev/null
  set +e
  /usr/bin/time -f "$ply verify   %e s wall %M KB peak" "$bin" verify "$out/${ply}_seq.nc" \
    --scene "$scene" >"$out/$ply.verify.txt"
  rc=$?
  set -e
  echo "$ply verify exit $rc"
  [[ $rc -eq 0 ]] || { status=1; tail -5 "$out/$ply.verify.txt"; }
  python3 - "$out/$ply.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
t = r["totals"]
print("  %d courses, %d sets, %d reversed; solver %s" % (len(r["order"]), len(r["sets"]),
      sum(1 for v in r["order"] if v["reversed"]), r["solver"]))
for key, unit in (("axes", ""), ("time_s", "s"), ("tool_mm", "mm"), ("timed_s", "s")):
    b, a = t["offpart_before"][key], t["offpart_after"][key]
    print("  off-part %-7s %10.3f -> %10.3f %-2s (%+.1f %%)" % (key, b, a, unit,
          100.0 * (a - b) / b if b else 0.0))
f = t["flown_tool_mm"]
print("  flown off-part %.0f -> %.0f mm; lay-up timed %.2f s" % (f["offpart_before"],
      f["offpart_after"], t["layup"]["timed_s"]))
PY
done
exit $status
