#!/usr/bin/env bash
# Builds one libFuzzer target of tests/fuzz with clang (address,undefined; ./build-fuzz) and
# runs it for SECONDS, seeded from its corpus (tests/fuzz/corpus/TARGET + bundled data).
# New inputs go to build-fuzz/corpus/TARGET, crashes to build-fuzz/artifacts/TARGET/.
# Usage: scripts/fuzz.sh TARGET SECONDS [libFuzzer flags...]
#   TARGET: program | dialect | head_spec | scene | stl | trace | afp_program
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
if (($# < 2)); then
  echo "usage: $0 program|dialect|head_spec|scene|stl|trace|afp_program SECONDS [libFuzzer flags...]" >&2
  exit 2
fi
target=$1 seconds=$2
shift 2

launcher=()
if command -v ccache >/dev/null; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
fi
if [[ ! -f build-fuzz/CMakeCache.txt ]]; then
  CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=Fuzz \
    -DCMAKE_CXX_FLAGS_FUZZ="-O1 -g" -DCMAKE_C_FLAGS_FUZZ="-O1 -g" -DSTITCHSIM_FUZZ=ON \
    -DSTITCHSIM_BUILD_TESTS=OFF -DSTITCHSIM_BUILD_BENCH=OFF "${launcher[@]}" >/dev/null
fi
cmake --build build-fuzz --target "fuzz_$target"

corpus=build-fuzz/corpus/$target artifacts=build-fuzz/artifacts/$target
mkdir -p "$corpus" "$artifacts"
# Seed folders are corpus arguments; single seed files go through -seed_inputs.
dirs=() files=()
while IFS= read -r seed; do
  [[ -z $seed ]] && continue
  if [[ -d $seed ]]; then dirs+=("$seed"); else files+=("$seed"); fi
done <"build-fuzz/tests/fuzz/fuzz_$target.seeds"
seed_flag=()
if ((${#files[@]})); then seed_flag=(-seed_inputs="$(IFS=,; echo "${files[*]}")"); fi
export ASAN_OPTIONS="detect_leaks=1:strict_string_checks=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# One scratch folder per run (the scene and STL targets write their inputs there).
TMPDIR=$(mktemp -d)
export TMPDIR
trap 'rm -rf "$TMPDIR"' EXIT
"build-fuzz/tests/fuzz/fuzz_$target" "$corpus" "${dirs[@]}" "${seed_flag[@]}" \
  -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=16384 \
  -artifact_prefix="$root/$artifacts/" -print_final_stats=1 "$@"
