#!/usr/bin/env bash
# Verifies every bundled scene's programme (every path, coupled, decoupled and auto; AFP at
# incline 0 and auto) and both whole-wing strategies (the jump raster, 1.66 M stitches, and the
# coarse serpentine) four ways, and compares the reports (text, JSON, JUnit) byte for byte:
#   --jobs 1, --jobs 2, --jobs 7, and 8 shards (`verify --shard I/8`) merged by `report merge`.
#
#   bash scripts/parallel_reports.sh BIN [--no-wing | --wing-only] [CHUNK_LINES]
#
# CHUNK_LINES (default: verify's own) cuts the small programmes often too. Prints one line per
# programme; exit 1 if any report differs, 2 on a run that fails with bad input.
set -uo pipefail
BIN=$(realpath "$1")
WING=1
OTHERS=1
[[ ${2:-} == --no-wing ]] && WING=0
[[ ${2:-} == --wing-only ]] && OTHERS=0
CUT=()
[[ -n ${3:-} ]] && CUT=(--chunk-lines "$3")
ROOT=$(cd "$(dirname "$0")/.." && pwd)
cd "$ROOT"
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
differ=0

reports() {  # reports TAG CMD...: stdout, exit, JSON and JUnit of one run into $W/TAG.*
  local tag=$1
  shift
  "$@" --report "$W/$tag.json" --junit "$W/$tag.xml" >"$W/$tag.txt" 2>"$W/$tag.err"
  local rc=$?
  echo "exit $rc" >>"$W/$tag.txt"
  if ((rc >= 2)); then
    echo "parallel_reports: $tag: exit $rc" >&2
    cat "$W/$tag.err" >&2
    exit 2
  fi
}

check() {  # check NAME PROG SCENE
  local name=$1 nc=$2 scene=$3 t0 t1
  t0=$(date +%s.%N)
  reports "$name.j1" "$BIN" verify "$nc" --scene "$scene" -q --jobs 1
  t1=$(date +%s.%N)
  reports "$name.j2" "$BIN" verify "$nc" --scene "$scene" -q --jobs 2 "${CUT[@]}"
  reports "$name.j7" "$BIN" verify "$nc" --scene "$scene" -q --jobs 7 "${CUT[@]}"
  local parts=()
  for i in 1 2 3 4 5 6 7 8; do
    "$BIN" verify "$nc" --scene "$scene" -q --jobs 1 "${CUT[@]}" --shard "$i/8" \
      --part "$W/$name.part$i.json" 2>"$W/$name.shard.err" || {
      echo "parallel_reports: $name: shard $i failed" >&2
      cat "$W/$name.shard.err" >&2
      exit 2
    }
    parts+=("$W/$name.part$i.json")
  done
  reports "$name.m8" "$BIN" report merge "${parts[@]}"
  local verdict="same"
  for way in j2 j7 m8; do
    for ext in txt json xml; do
      if ! cmp -s "$W/$name.j1.$ext" "$W/$name.$way.$ext"; then
        verdict="DIFFERS ($way .$ext)"
        differ=1
      fi
    done
  done
  printf '%-60s %s  (%d lines, --jobs 1 %.1f s)\n' "$name" "$verdict" "$(wc -l <"$nc")" \
    "$(echo "$t1 - $t0" | bc)"
  rm -f "$W/$name".*.json "$W/$name".*.xml
}

# shellcheck source=lib/scenes.sh
source "$ROOT/scripts/lib/scenes.sh"

for scene in scenes/*.yaml; do
  base=$(basename "$scene" .yaml)
  head=$(head_of "$scene")
  if [[ $base == wing_cover ]]; then
    ((WING)) || continue
    "$BIN" plan raster --scene "$scene" --strategy jump -o "$W/wing.jump.nc" --quiet >/dev/null
    check wing_cover.jump "$W/wing.jump.nc" "$scene"
    rm -f "$W/wing.jump.nc"
    "$BIN" plan raster --scene "$scene" --strategy serpentine --pitch 0.5 --row-spacing 2 \
      -o "$W/wing.serp.nc" --quiet >/dev/null
    check wing_cover.serpentine_coarse "$W/wing.serp.nc" "$scene"
  elif ((!OTHERS)); then
    continue
  elif [[ $head == afp ]]; then
    for incline in 0 auto; do
      nc=$W/$base.$incline.nc
      "$BIN" plan afp --scene "$scene" --lay-angle 45 --incline "$incline" -o "$nc" \
        --quiet >/dev/null 2>&1
      [[ -f $nc ]] && check "$base.incline_$incline" "$nc" "$scene"
    done
  else
    for path in $(paths_of "$scene"); do
      for mode in coupled decoupled auto; do
        nc=$W/$base.$path.$mode.nc
        "$BIN" plan stitch --scene "$scene" --path "$path" --mode "$mode" -o "$nc" \
          --quiet >/dev/null || exit 2
        check "$base.$path.$mode" "$nc" "$scene"
      done
    done
  fi
done
((differ)) && echo "parallel_reports: some reports differ" && exit 1
echo "parallel_reports: every report byte-identical"
