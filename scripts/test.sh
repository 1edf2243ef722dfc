#!/usr/bin/env bash
# The whole test suite (README's test command, after `scripts/setup.sh --tests`): ctest in
# ./build, then scripts/sanitize.sh (the suite under ASan + UBSan in ./build-asan). Ends with
# the wall time of each stage, set-up's included (setup.sh leaves its figures in
# build/setup_times.txt). Exit: ctest's or the sanitizer run's failure, else 0.
set -uo pipefail
cd "$(dirname "$0")/.."

t0=$(date +%s)
ctest --test-dir build --output-on-failure --parallel "$(nproc)"
normal=$?
t1=$(date +%s)
sanitized=1
if ((normal == 0)); then
  bash scripts/sanitize.sh
  sanitized=$?
fi
t2=$(date +%s)

echo
echo "== wall time per stage =="
[[ -f build/setup_times.txt ]] && cat build/setup_times.txt
echo "tests       $((t1 - t0)) s (ctest, exit $normal)"
if ((normal == 0)); then
  [[ -f build-asan/sanitize_times.txt ]] && cat build-asan/sanitize_times.txt
  echo "sanitizers  $((t2 - t1)) s (exit $sanitized)"
else
  echo "sanitizers  not run (the normal suite failed)"
fi
((normal == 0)) || exit "$normal"
exit "$sanitized"
