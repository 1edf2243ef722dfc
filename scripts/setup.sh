#!/usr/bin/env bash
# stitchsim set-up: installs the Debian 12 packages the build needs (as root, idempotent) and
# builds everything into ./build. Used by both README commands and by .ci/run.
set -euo pipefail
cd "$(dirname "$0")/.."

PACKAGES=(
  build-essential cmake ninja-build pkg-config python3 python3-yaml  # yaml: ctest ci_doc
  libmujoco-dev libqhull-dev libeigen3-dev liburdfdom-dev libfcl-dev libosmesa6-dev
  libgtest-dev libgmock-dev libbenchmark-dev libyaml-cpp-dev libcli11-dev
  nlohmann-json3-dev libpng-dev libfreetype-dev fonts-dejavu-core  # snapshot text (render/text.h)
  libocct-foundation-dev libocct-modeling-data-dev libocct-modeling-algorithms-dev
  libocct-data-exchange-dev libtbb-dev  # OpenCASCADE (CAD surfaces); its CMake targets need TBB
  clang libclang-rt-14-dev  # scripts/fuzz.sh: libFuzzer and clang's sanitizer runtimes
  chromium libjs-three  # verify --html: three.js inlined; tests/browser: headless Chromium
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  SUDO=""
  [[ $(id -u) -eq 0 ]] || SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# tests/browser (the HTML report in headless Chromium): Node from Debian, playwright-core pinned.
if ! command -v node >/dev/null; then
  SUDO=""
  [[ $(id -u) -eq 0 ]] || SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends nodejs npm
fi
if [[ ! -d tests/browser/node_modules ]]; then
  npm ci --prefix tests/browser --silent --no-audit --no-fund
fi

BUILD_TYPE=${STITCHSIM_BUILD_TYPE:-Release}
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE="$BUILD_TYPE"
cmake --build build --parallel "$(nproc)"
