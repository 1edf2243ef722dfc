#!/usr/bin/env bash
# Plans and verifies every bundled scene with one stitchsim binary and keeps every report
# (text, JSON, JUnit) and programme, so two builds can be compared byte for byte:
#
#   bash scripts/scene_reports.sh BIN OUT [--no-wing | --wing-only]
#   diff -r OUT_a OUT_b
#
# Stitch scenes: every path, coupled, decoupled and auto. AFP scenes: --lay-angle 45 at
# incline 0 and auto. The wing: the jump raster of the whole cover (1.66 M stitches) and a
# coarse serpentine one (--no-wing leaves the wing out: minutes instead of most of an hour).
# Runs from the repository root with relative paths, so reports name the same files
# whichever checkout made them. Exit 0 even when a verdict is FAIL (the verdict is part of
# what is compared); a bad-input or internal error (exit 2 or 3) stops the script.
set -uo pipefail
BIN=$(realpath "$1")
OUT=$(realpath -m "$2")
WING=1
OTHERS=1
[[ ${3:-} == --no-wing ]] && WING=0
[[ ${3:-} == --wing-only ]] && OTHERS=0
ROOT=$(cd "$(dirname "$0")/.." && pwd)
cd "$ROOT"
W=out/scene-reports
((OTHERS)) || W=out/scene-reports-wing  # may run beside a run of the others
rm -rf "$W" && mkdir -p "$W" "$OUT"

run() {  # run NAME CMD...: records stdout+exit in $W/NAME.txt
  local name=$1
  shift
  "$@" >"$W/$name.txt" 2>"$W/$name.err"
  local rc=$?
  echo "exit $rc" >>"$W/$name.txt"
  if ((rc >= 2)); then
    echo "scene_reports: $name: exit $rc" >&2
    cat "$W/$name.err" >&2
    exit 1
  fi
}

verify() {  # verify NAME SCENE [extra verify args]
  local name=$1 scene=$2
  shift 2
  run "$name.verify" "$BIN" verify "$W/$name.nc" --scene "$scene" --report "$W/$name.json" \
    --junit "$W/$name.xml" "$@"
}

# shellcheck source=lib/scenes.sh
source "$ROOT/scripts/lib/scenes.sh"

for scene in scenes/*.yaml; do
  base=$(basename "$scene" .yaml)
  head=$(head_of "$scene")
  if [[ $base == wing_cover ]]; then
    ((WING)) || continue
    name=$base.jump
    run "$name.plan" "$BIN" plan raster --scene "$scene" --strategy jump -o "$W/$name.nc"
    verify "$name" "$scene"
    name=$base.serpentine_coarse
    run "$name.plan" "$BIN" plan raster --scene "$scene" --strategy serpentine \
      --pitch 0.5 --row-spacing 2 -o "$W/$name.nc"
    verify "$name" "$scene"
  elif ((!OTHERS)); then
    continue
  elif [[ $head == afp ]]; then
    for incline in 0 auto; do
      name=$base.incline_$incline
      run "$name.plan" "$BIN" plan afp --scene "$scene" --lay-angle 45 --incline "$incline" \
        -o "$W/$name.nc"
      # A course the cell cannot lay (exit 1, e.g. naca_wing's through the nose) writes none.
      [[ -f $W/$name.nc ]] && verify "$name" "$scene"
    done
  else
    for path in $(paths_of "$scene"); do
      for mode in coupled decoupled auto; do
        name=$base.$path.$mode
        run "$name.plan" "$BIN" plan stitch --scene "$scene" --path "$path" --mode "$mode" \
          -o "$W/$name.nc"
        verify "$name" "$scene"
      done
    done
  fi
done
rm -rf "$OUT" && mv "$W" "$OUT"
echo "scene_reports: $(ls "$OUT"/*.verify.txt | wc -l) verify runs in $OUT"
