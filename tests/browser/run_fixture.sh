#!/usr/bin/env bash
# Builds the synthetic HTML report (make_fixture.py) and checks it in headless Chromium
# (check_report.mjs). Usage: tests/browser/run_fixture.sh [OUT_DIR] [make_fixture.py options]
# OUT_DIR receives fixture.html and the screenshots (default: a scratch folder, removed).
# Exit 77 (ctest: skipped) when node, Chromium or the npm packages are missing.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
if ! command -v node >/dev/null || [[ ! -x /usr/bin/chromium ]] ||
   [[ ! -d "$here/node_modules/playwright-core" ]] ||
   [[ ! -f /usr/share/javascript/three/three.min.js ]]; then
  echo "run_fixture: needs node, /usr/bin/chromium, libjs-three and 'npm ci --prefix tests/browser'"
  exit 77
fi
out="${1:-}"
[[ $# -gt 0 ]] && shift
if [[ -z "$out" ]]; then
  out="$(mktemp -d "/tmp/stitchsim-html-$$-XXXX")"
  trap 'rm -rf "$out"' EXIT
fi
mkdir -p "$out"
python3 "$here/make_fixture.py" "$out/fixture.html" "$@" >&2
node "$here/check_report.mjs" "$out/fixture.html" --out "$out" --expect-finding
# Malformed data: the page must say so (no blank page, no console error).
python3 "$here/make_fixture.py" "$out/broken.html" --broken >&2
node "$here/check_report.mjs" "$out/broken.html" --out "$out" --expect-shown-error >&2
