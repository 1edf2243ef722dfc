#!/usr/bin/env bash
# stitchsim set-up: installs the Debian 12 packages (as root, idempotent) and builds into ./build.
# One entry point for both README commands and .ci/run:
#
#   bash scripts/setup.sh           the CLI only: run-time packages, the `stitchsim` target
#   bash scripts/setup.sh --tests   also the test tool chain (GoogleTest, Benchmark, clang and
#                                   its sanitizer runtimes, Chromium, Node, playwright-core) and
#                                   every target: test executables, benches, fuzz replays
#
# Prints how long the packages and the build took.
set -euo pipefail
cd "$(dirname "$0")/.."

TESTS=0
for arg in "$@"; do
  case $arg in
    --tests) TESTS=1 ;;
    *) echo "setup: unknown option $arg (use --tests)" >&2; exit 2 ;;
  esac
done

# What the CLI needs to build and run (three.js is embedded into `verify --html` at build time).
PACKAGES=(
  build-essential cmake ninja-build pkg-config
  libmujoco-dev libqhull-dev libeigen3-dev liburdfdom-dev libfcl-dev libosmesa6-dev
  libyaml-cpp-dev libcli11-dev nlohmann-json3-dev libpng-dev
  libfreetype-dev fonts-dejavu-core  # snapshot text (render/text.h)
  libocct-foundation-dev libocct-modeling-data-dev libocct-modeling-algorithms-dev
  libocct-data-exchange-dev libtbb-dev  # OpenCASCADE (CAD surfaces); its CMake targets need TBB
  libjs-three                           # verify --html: three.js inlined at build time
)
# What the test suite adds.
TEST_PACKAGES=(
  python3 python3-yaml                 # ctest size_bounds, ci_doc, readme_tours
  libgtest-dev libgmock-dev libbenchmark-dev
  clang libclang-rt-14-dev             # scripts/fuzz.sh: libFuzzer and clang's sanitizer runtimes
  chromium                             # tests/browser: the HTML report in headless Chromium
)
((TESTS)) && PACKAGES+=("${TEST_PACKAGES[@]}")

SUDO=""
[[ $(id -u) -eq 0 ]] || SUDO="sudo"
t0=$(date +%s)
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
# tests/browser: Node from Debian when the machine has none.
((TESTS)) && ! command -v node >/dev/null && missing+=(nodejs npm)
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
# tests/browser: playwright-core, pinned in its package-lock.json.
if ((TESTS)) && [[ ! -d tests/browser/node_modules ]]; then
  npm ci --prefix tests/browser --silent --no-audit --no-fund
fi
t1=$(date +%s)

BUILD_TYPE=${STITCHSIM_BUILD_TYPE:-Release}
if ((TESTS)); then
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE="$BUILD_TYPE" \
    -DSTITCHSIM_BUILD_TESTS=ON -DSTITCHSIM_BUILD_BENCH=ON >/dev/null
  cmake --build build --parallel "$(nproc)"
else
  # A build folder configured for the tests keeps its options (same objects, nothing rebuilt).
  opts=()
  [[ -f build/CMakeCache.txt ]] || opts=(-DSTITCHSIM_BUILD_TESTS=OFF -DSTITCHSIM_BUILD_BENCH=OFF)
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE="$BUILD_TYPE" "${opts[@]}" >/dev/null
  cmake --build build --parallel "$(nproc)" --target stitchsim
fi
t2=$(date +%s)
echo "setup: packages $((t1 - t0)) s, build $((t2 - t1)) s"
# scripts/test.sh prints these at the end of a CI run.
printf 'setup       %d s (packages)\nbuild       %d s\n' $((t1 - t0)) $((t2 - t1)) \
  >build/setup_times.txt
