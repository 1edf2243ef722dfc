#!/usr/bin/env bash
# Timed CLI runs of `stitchsim sequence` (issue 13, done-when 5): 1,000 courses in one
# precedence set (target 2 s) and 10,000 courses in a 40-ply programme (target 20 s), wall time
# and peak memory (GNU time), each beside `stitchsim check` of the same programme in the same
# run (the baseline: reading it), RUNS times each.
#   bash bench/sequence_cli.sh [BIN] [RUNS]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
bin=${1:-$here/../build/app/stitchsim}
runs=${2:-3}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
python3 "$here/make_sequence_bench.py" "$out/one" --plies 4 --courses-per-ply 250 --layout beside
python3 "$here/make_sequence_bench.py" "$out/big" --plies 40 --courses-per-ply 250
for case in one/seq_bench_beside_4x250 big/seq_bench_stacked_40x250; do
  prog=$out/$case.nc scene=$out/$case.yaml
  for ((r = 1; r <= runs; r++)); do
    /usr/bin/time -f "$case check    %e s wall %U s user %M KB peak" "$bin" check "$prog" >/dev/null
    /usr/bin/time -f "$case sequence %e s wall %U s user %M KB peak" "$bin" sequence "$prog" \
      --scene "$scene" --bidirectional -o "$out/seq.nc" --report "$out/seq.json" >"$out/seq.txt"
  done
  python3 - "$out/seq.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
t = r["totals"]
print("  %d sets, %d courses; off-part axes %.1f -> %.1f; flown off-part %.0f -> %.0f mm"
      % (len(r["sets"]), len(r["order"]), t["offpart_before"]["axes"], t["offpart_after"]["axes"],
         t["flown_tool_mm"]["offpart_before"], t["flown_tool_mm"]["offpart_after"]))
PY
done
