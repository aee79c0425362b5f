#!/usr/bin/env bash
# Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#
# The same boxes on every machine: track_sequence on a few clips, with OpenCV's run-time CPU
# dispatch as it is, limited to the baseline instruction set, and on one thread, must write
# byte-identical outputs (boxes and confidence of every frame), --init gt and --init auto. Clips:
# two generated scenes, and antiuav_ir_35, Vase and lasot_airplane-1 (whole clips) from
# ../shared/sequences when it is there (skipped with a message when not).
#   OT_BUILD_DIR  the catkin build (default _build)
set -euo pipefail
cd "$(dirname "$0")/../.."
export PATH=/usr/bin:/bin:/usr/sbin:/sbin:$PATH
BUILD=${OT_BUILD_DIR:-_build}
BIN=$BUILD/devel/lib/obstacle_tracker
TMP=$(mktemp -d /tmp/ot_stable_XXXXXX)
trap 'rm -rf "$TMP"' EXIT
for tool in track_sequence generate_scene; do
  [ -x "$BIN/$tool" ] || { echo "35-stable-numbers: $BIN/$tool not built"; exit 1; }
done

clips=()
"$BIN/generate_scene" --scenario crossing+jerk --seed 3 --frames 150 --size 480x360 --quiet --out "$TMP/data/crossing_jerk"
"$BIN/generate_scene" --scenario bird --seed 3 --frames 150 --size 480x360 --quiet --out "$TMP/data/bird"
clips+=("$TMP/data/crossing_jerk" "$TMP/data/bird")
SHARED=../shared/sequences
for c in antiuav_ir_35 Vase lasot_airplane-1; do
  if [ -f "$SHARED/$c/groundtruth_rect.txt" ]; then
    clips+=("$SHARED/$c")
  else
    echo "35-stable-numbers: $SHARED/$c not found: skipped (the research clips live outside the package)"
  fi
done

# Each setting: a name and the environment it runs in. OpenCV's feature names as it spells them.
settings=("dispatch-limited OPENCV_CPU_DISABLE=AVX512F,AVX2,FMA3,AVX,FP16,POPCNT"
          "one-thread OPENCV_FOR_THREADS_NUM=1")
status=0
for clip in "${clips[@]}"; do
  name=$(basename "$clip")
  for init in gt auto; do
    "$BIN/track_sequence" "$clip" --init "$init" --quiet --output "$TMP/$name.$init.default.txt"
    for s in "${settings[@]}"; do
      label=${s%% *}
      env ${s#* } "$BIN/track_sequence" "$clip" --init "$init" --quiet --output "$TMP/$name.$init.$label.txt" 2>/dev/null
      if cmp -s "$TMP/$name.$init.default.txt" "$TMP/$name.$init.$label.txt"; then
        echo "35-stable-numbers: $name --init $init: $label identical"
      else
        echo "FAILED: $name --init $init: $label gives other boxes; first differing lines:"
        diff "$TMP/$name.$init.default.txt" "$TMP/$name.$init.$label.txt" | head -6
        status=1
      fi
    done
  done
done
exit $status
