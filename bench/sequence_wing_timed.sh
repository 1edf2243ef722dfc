#!/usr/bin/env bash
# The wing's plies ordered by the timed measure (issue 28, done-when 4): each case (a ply of
# scenes/naca_wing.yaml, or plies joined by commas: one programme) planned by `plan ply`,
# sequenced with `--cost timed --bidirectional`, the result verified (`verify` exit 0 wanted);
# per case the off-part cost before and after in every measure, the wall times, and the
# saving on the time law that `sequence` predicts beside the one `verify` measures (its
# cycle_time_timed_s of the programme's own order written with the same kind of off-part
# moves, `sequence --order`, minus that of the new order).
#   bash bench/sequence_wing_timed.sh [BIN] [CASE ...]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
bin=${1:-$here/../build/app/stitchsim}
shift || true
scene=$here/../scenes/naca_wing.yaml
cases=("$@")
[[ ${#cases[@]} -gt 0 ]] || cases=(upper_0 upper_45 upper_skin_0 upper_0,upper_45)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
status=0
verify_timed() {  # programme, tag -> verify's exit code; its report in $out/$2.verify.json
  set +e
  /usr/bin/time -f "$2 verify   %e s wall %M KB peak" "$bin" verify "$1" --scene "$scene" \
    --report "$out/$2.verify.json" >"$out/$2.verify.txt" 2>"$out/$2.verify.err"
  local rc=$?
  set -e
  grep "verify   " "$out/$2.verify.err" || true
  echo "$2 verify exit $rc"
  [[ $rc -eq 0 ]] || { status=1; tail -5 "$out/$2.verify.txt"; }
}
for case in "${cases[@]}"; do
  name=${case//,/+}
  ply_args=()
  IFS=, read -ra plies <<<"$case"
  for p in "${plies[@]}"; do ply_args+=(--ply "$p"); done
  "$bin" plan ply --scene "$scene" "${ply_args[@]}" -o "$out/$name.nc" >/dev/null 2>&1
  /usr/bin/time -f "$name sequence %e s wall %M KB peak" "$bin" sequence "$out/$name.nc" \
    --scene "$scene" --cost timed --bidirectional --quiet -o "$out/${name}_seq.nc" \
    --report "$out/$name.json" >/dev/null
  python3 - "$out/$name.json" "$out/$name.order.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
order = sorted(({"ply": v["ply"], "course": v["course"]} for v in r["order"]),
               key=lambda v: (v["ply"], v["course"]))
json.dump({"order": order}, open(sys.argv[2], "w"))
PY
  "$bin" sequence "$out/$name.nc" --scene "$scene" --quiet --order "$out/$name.order.json" \
    -o "$out/${name}_orig.nc" >/dev/null
  verify_timed "$out/${name}_seq.nc" "$name"
  verify_timed "$out/${name}_orig.nc" "${name}_orig"
  python3 - "$out/$name.json" "$out/$name.verify.json" "$out/${name}_orig.verify.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
t = r["totals"]
print("  %d courses, %d sets, %d reversed; solver %s, %.2f s in the run" % (len(r["order"]),
      len(r["sets"]), sum(1 for v in r["order"] if v["reversed"]), r["solver"], r["seconds"]))
for key, unit in (("axes", ""), ("time_s", "s"), ("tool_mm", "mm"), ("timed_s", "s")):
    b, a = t["offpart_before"][key], t["offpart_after"][key]
    print("  off-part %-7s %10.3f -> %10.3f %-2s (%+.1f %%)" % (key, b, a, unit,
          100.0 * (a - b) / b if b else 0.0))
f = t["flown_tool_mm"]
print("  flown off-part %.0f -> %.0f mm; lay-up timed %.2f s" % (f["offpart_before"],
      f["offpart_after"], t["layup"]["timed_s"]))
try:
    after = json.load(open(sys.argv[2]))["cycle_time_timed_s"]
    before = json.load(open(sys.argv[3]))["cycle_time_timed_s"]
    print("  saving on the time law: sequence predicts %.2f s, verify measures %.2f s "
          "(cycle %.2f -> %.2f s)" % (t["offpart_before"]["timed_s"] - t["offpart_after"]["timed_s"],
                                     before - after, before, after))
except (OSError, KeyError, ValueError):
    print("  (no verify report)")
PY
done
exit $status
