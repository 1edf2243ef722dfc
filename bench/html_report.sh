#!/usr/bin/env bash
# The HTML report of the whole wing (1.66 M stitches), without and with a fault: how long
# `verify --html` takes beside the same run without it, the page's size, and how long headless
# Chromium takes to open it and pass the browser check (tests/browser/check_report.mjs):
#   bash bench/html_report.sh BIN [OUT_DIR]
set -euo pipefail
BIN=$(realpath "$1")
OUT=$(realpath -m "${2:-out/bench-html}")
ROOT=$(cd "$(dirname "$0")/.." && pwd)
cd "$ROOT"
mkdir -p "$OUT"
scene=scenes/wing_cover.yaml
[[ -f $OUT/wing.nc ]] || "$BIN" plan raster --scene $scene --strategy jump --quiet -o "$OUT/wing.nc"
t0=$(date +%s.%N)
"$BIN" verify "$OUT/wing.nc" --scene $scene --quiet --report "$OUT/plain.json" >/dev/null
t1=$(date +%s.%N)
"$BIN" verify "$OUT/wing.nc" --scene $scene --quiet --report "$OUT/html.json" \
  --html "$OUT/wing.html" >/dev/null
t2=$(date +%s.%N)
cmp -s "$OUT/plain.json" "$OUT/html.json" || { echo "html_report: reports differ" >&2; exit 1; }
python3 -c "print(f'verify: {$t1 - $t0:.1f} s; verify --html: {$t2 - $t1:.1f} s; page \
{$(stat -c %s "$OUT/wing.html") / 1048576:.1f} MB')"
node tests/browser/check_report.mjs "$OUT/wing.html" --out "$OUT"
# The same wing with one stitch lifted 5 mm off the skin halfway (the last stitch of the first
# row piece after line 800000): a page with findings, so "go to this finding" is checked at
# wing scale too.
python3 - "$OUT/wing.nc" "$OUT/wing_fault.nc" <<'PY'
import sys
src, dst = sys.argv[1], sys.argv[2]
with open(src) as f:
    lines = f.read().split('\n')
k = next(i for i in range(800000, len(lines)) if lines[i] == 'M11' and lines[i - 1].startswith('G1 ')) - 1
lines[k] = ' '.join('Z%.6f' % (float(w[1:]) + 5.0) if w.startswith('Z') else w for w in lines[k].split())
with open(dst, 'w') as f:
    f.write('\n'.join(lines))
print('lifted line', k + 1)
PY
"$BIN" verify "$OUT/wing_fault.nc" --scene $scene --quiet --html "$OUT/wing_fault.html" >/dev/null ||
  [[ $? == 1 ]]
node tests/browser/check_report.mjs "$OUT/wing_fault.html" --out "$OUT/fault" --expect-finding
