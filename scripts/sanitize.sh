#!/usr/bin/env bash
# The whole test suite under AddressSanitizer + UndefinedBehaviorSanitizer (with LeakSanitizer),
# in ./build-asan (-O1 -g, assertions on). Any report fails the test that reached it.
# Run after scripts/setup.sh (which installs the packages). Extra arguments go to ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD

launcher=()
if command -v ccache >/dev/null; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
fi

# The only suppression is libOSMesa's own leak in OSMesaMakeCurrent (tests/lsan.supp).
export ASAN_OPTIONS="detect_leaks=1:check_initialization_order=1:strict_string_checks=1:abort_on_error=0:halt_on_error=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export LSAN_OPTIONS="suppressions=$root/tests/lsan.supp:print_suppressions=0"

start=$(date +%s)
# -g1: line tables, enough for the stack traces of a report, at three quarters of -g's compile
# time (docs/ci.md, "Build time").
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=Sanitize \
  -DCMAKE_CXX_FLAGS_SANITIZE="-O1 -g1" -DCMAKE_C_FLAGS_SANITIZE="-O1 -g1" \
  -DSTITCHSIM_SANITIZE=address,undefined -DSTITCHSIM_BUILD_BENCH=OFF -DSTITCHSIM_TEST_TIMEOUT=600 \
  "${launcher[@]}"
cmake --build build-asan --parallel "$(nproc)"
built=$(date +%s)
# Left out (docs/ci.md, "The sanitizer run"): `slow`, whole wing windows and plies whose code
# the smaller tests run too; `browser`, the page in Chromium (the C++ that writes it runs in
# html_report_cli_test); `docs`, the README tours.
rc=0
ctest --test-dir build-asan --output-on-failure --parallel "$(nproc)" -LE '^(slow|browser|docs)$' \
  "$@" || rc=$?
end=$(date +%s)
echo "sanitize: build $((built - start)) s, tests $((end - built)) s (address,undefined)"
printf 'asan build  %d s\nasan tests  %d s\n' $((built - start)) $((end - built)) \
  >build-asan/sanitize_times.txt
exit $rc
