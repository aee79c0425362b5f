#!/usr/bin/env bash
# Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#
# Do the scores depend on the machine? track_sequence on a few clips, with OpenCV's run-time CPU
# dispatch as it is, limited to the baseline instruction set, with glibc's libm limited the same
# way, and on one thread; reports OTB
# precision at 20 px and success AUC of each (score_boxes), --init gt and --init auto,
# whether they agree within 0.02 and whether the outputs are byte-identical; exits non-zero when
# one does not agree (docs/portability.md; CI: scripts/extra_tests.d/45-stable-numbers.sh). Clips:
# two generated scenes, and antiuav_ir_35, Vase and lasot_airplane-1 (whole clips) from
# ../shared/sequences when it is there (skipped with a message when not).
#   OT_BUILD_DIR  the catkin build (default _build)
set -euo pipefail
cd "$(dirname "$0")/.."
export PATH=/usr/bin:/bin:/usr/sbin:/sbin:$PATH
BUILD=${OT_BUILD_DIR:-_build}
BIN=$BUILD/devel/lib/obstacle_tracker
TMP=$(mktemp -d /tmp/ot_stable_XXXXXX)
trap 'rm -rf "$TMP"' EXIT
for tool in track_sequence generate_scene score_boxes; do
  [ -x "$BIN/$tool" ] || { echo "stable_numbers: $BIN/$tool not built"; exit 1; }
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
    echo "stable_numbers: $SHARED/$c not found: skipped (the research clips live outside the package)"
  fi
done

# Each setting: a name and the environment it runs in. OpenCV's feature names as it spells them.
# libm-baseline: glibc's libm without its FMA / AVX2 variants (exp, log, pow, cos pick them by
# CPU), as on a CPU without them.
settings=("dispatch-limited OPENCV_CPU_DISABLE=AVX512F,AVX2,FMA3,AVX,FP16,POPCNT"
          "libm-baseline GLIBC_TUNABLES=glibc.cpu.hwcaps=-AVX2,-FMA"
          "one-thread OPENCV_FOR_THREADS_NUM=1")
score() {  # P@20 and AUC of a boxes file against a ground truth: "p20 auc"
  "$BIN/score_boxes" "$1" --gt "$2" |
    awk -F= '$1 == "precision20" { p = $2 } $1 == "auc" { a = $2 } END { printf "%.3f %.3f\n", p, a }'
}
status=0
for clip in "${clips[@]}"; do
  name=$(basename "$clip")
  gt=$clip/groundtruth_rect.txt
  for init in gt auto; do
    "$BIN/track_sequence" "$clip" --init "$init" --quiet --output "$TMP/$name.$init.default.txt"
    read -r p_ref auc_ref < <(score "$TMP/$name.$init.default.txt" "$gt")
    for s in "${settings[@]}"; do
      label=${s%% *}
      out=$TMP/$name.$init.$label.txt
      env ${s#* } "$BIN/track_sequence" "$clip" --init "$init" --quiet --output "$out" 2>/dev/null
      read -r p auc < <(score "$out" "$gt")
      same=$(cmp -s "$TMP/$name.$init.default.txt" "$out" && echo "byte-identical" || echo "boxes differ")
      verdict=$(awk -v a="$auc_ref" -v b="$auc" -v c="$p_ref" -v d="$p" \
        'function abs(x) { return x < 0 ? -x : x } BEGIN { print (abs(a - b) <= 0.02 && abs(c - d) <= 0.02) ? "ok" : "FAILED" }')
      echo "$verdict: $name --init $init, $label: P@20 $p_ref / $p, AUC $auc_ref / $auc ($same)"
      [ "$verdict" = ok ] || status=1
    done
  done
done
exit $status
