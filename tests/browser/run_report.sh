#!/usr/bin/env bash
# Plans a bundled scene, verifies it with --html and checks the page in headless Chromium:
#   tests/browser/run_report.sh STITCHSIM SCENE "PLAN ARGS" EXIT [OUT_DIR]
# e.g. run_report.sh build/app/stitchsim scenes/circle_8in.yaml "stitch --mode coupled" 1.
# EXIT is the verdict verify must give (0 clean, 1 findings); any other fails the test, and a
# programme with findings must also pass the "go to this finding" check. OUT_DIR keeps the
# programme, the page and the screenshots (default: a scratch folder, removed). A fibre-placement
# ply (PLAN ARGS "ply ...") is planned with --tows-csv and its laid tows are checked too.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
bin="$1" scene="$2" plan="$3" want="$4" out="${5:-}"
if [[ $want != 0 && $want != 1 ]]; then
  echo "run_report: EXIT must be 0 or 1, not '$want'" >&2
  exit 2
fi
if [[ -z "$out" ]]; then
  out="$(mktemp -d "/tmp/stitchsim-report-$$-XXXX")"
  trap 'rm -rf "$out"' EXIT
fi
mkdir -p "$out"
afp=()
if [[ $plan == ply\ * ]]; then
  plan="$plan --tows-csv $out/tows.csv"
  afp=(--afp-csv "$out/tows.csv" --afp-program "$out/prog.nc")
fi
# shellcheck disable=SC2086  # PLAN ARGS are words
"$bin" plan $plan --scene "$scene" --quiet -o "$out/prog.nc" >/dev/null
rc=0
"$bin" verify "$out/prog.nc" --scene "$scene" --quiet --html "$out/report.html" \
  --report "$out/report.json" >/dev/null || rc=$?
if ((rc != want)); then
  echo "run_report: verify exit $rc, expected $want" >&2
  exit 1
fi
expect=()
((rc == 1)) && expect=(--expect-finding)
node "$here/check_report.mjs" "$out/report.html" --out "$out" "${expect[@]}" "${afp[@]}"
