#!/usr/bin/env bash
# Timed CLI runs for issue 15 (S11): the whole wing (jump raster, 1.66 M stitches; and the
# coarse serpentine), every rule with collision, `verify --jobs 1` and `--jobs 2` alternating
# RUNS times (this machine is noisy: compare within a pair), wall and user time, peak memory,
# the ratio; peak memory on a 10 % window of the jump raster beside the whole (memory must not
# grow with programme length); and the gaps between the plain progress lines of a captured
# (non-terminal) run.
#   bash bench/parallel_cli.sh BIN [RUNS]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
bin=$(realpath "${1:?BIN}")
runs=${2:-3}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
scene=$here/../scenes/wing_cover.yaml
"$bin" plan raster --scene "$scene" --strategy jump -o "$out/jump.nc" --quiet >/dev/null
"$bin" plan raster --scene "$scene" --strategy serpentine --pitch 0.5 --row-spacing 2 \
  -o "$out/serp.nc" --quiet >/dev/null
timed() {  # timed LABEL ARGS...: prints "LABEL wall user peak"
  local label=$1
  shift
  /usr/bin/time -f "%e %U %M" -o "$out/time" "$bin" verify "$@" --scene "$scene" -q \
    --report "$out/r.json" >/dev/null || true
  read -r wall user peak < <(tail -n 1 "$out/time")
  printf '%-22s %7.2f s wall %7.2f s user %7.0f MB peak\n' "$label" "$wall" "$user" \
    "$(echo "$peak / 1024" | bc -l)"
  echo "$wall" >"$out/last"
}
for prog in jump serp; do
  for ((r = 1; r <= runs; r++)); do
    timed "$prog --jobs 1" "$out/$prog.nc" --jobs 1
    w1=$(cat "$out/last")
    timed "$prog --jobs 2" "$out/$prog.nc" --jobs 2
    w2=$(cat "$out/last")
    printf '  %s pair %d: --jobs 2 / --jobs 1 = %.1f %%\n' "$prog" "$r" \
      "$(echo "100 * $w2 / $w1" | bc -l)"
  done
done
# Memory against programme length: a tenth of the jump raster, closed.
lines=$(wc -l <"$out/jump.nc")
{ head -n $((lines / 10)) "$out/jump.nc"; printf 'M11\nM30\n%%\n'; } >"$out/tenth.nc"
timed "jump/10 --jobs 2" "$out/tenth.nc" --jobs 2
timed "jump --jobs 7" "$out/jump.nc" --jobs 7
# Progress in a CI log: the time of each plain line (stderr is a pipe, not a terminal).
start=$(date +%s.%N)
"$bin" verify "$out/jump.nc" --scene "$scene" --jobs 2 --report "$out/r.json" 2>&1 >/dev/null |
  while IFS= read -r line; do
    printf '  +%5.1f s  %s\n' "$(echo "$(date +%s.%N) - $start" | bc -l)" "$line"
  done
