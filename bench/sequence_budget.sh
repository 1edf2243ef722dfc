#!/usr/bin/env bash
# Issue 28, Done-when 5: one precedence set of 1,000 courses (4 plies side by side, 250 courses
# each, bidirectional, --cost axes), sequenced with a 2 s and a 60 s time limit: the 2 s answer
# against the 60 s one (the aim: within 1 %), each with its wall time, peak memory and the
# report's lower bound. A timed CLI run, not a unit test; the machine should be otherwise idle.
#   bash bench/sequence_budget.sh [BIN] [SHORT_S] [LONG_S]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
bin=${1:-$here/../build/app/stitchsim}
short=${2:-2}
long=${3:-60}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
python3 "$here/make_sequence_bench.py" "$out/one" --plies 4 --courses-per-ply 250 --layout beside \
  >/dev/null
prog=$out/one/seq_bench_beside_4x250.nc scene=$out/one/seq_bench_beside_4x250.yaml
for t in "$short" "$long"; do
  /usr/bin/time -f "%e %M" -o "$out/time_$t" "$bin" sequence "$prog" --scene "$scene" \
    --bidirectional --time-limit "$t" -o "$out/seq_$t.nc" --report "$out/seq_$t.json" >/dev/null
done
python3 - "$out" "$short" "$long" <<'PY'
import json, sys
out, short, long_ = sys.argv[1:]
def load(t):
    r = json.load(open(f"{out}/seq_{t}.json"))
    wall, kb = open(f"{out}/time_{t}").read().split()
    s = r["sets"][0]
    return s["cost"], s["bound"], s["status"], s["seconds"], float(wall), int(kb) / 1024
c_long = load(long_)[0]
print("| time limit | set cost | above the long run | bound | stop | solver s | wall s | peak MB |")
print("|---|---|---|---|---|---|---|---|")
for t in (short, long_):
    c, b, st, secs, wall, mb = load(t)
    print(f"| {t} s | {c:.4f} | {100 * (c - c_long) / c_long:+.3f} % | {b:.4f} | {st} | "
          f"{secs:.2f} | {wall:.2f} | {mb:.0f} |")
PY
