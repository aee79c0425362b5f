#!/usr/bin/env bash
# Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#
# The evaluation tool end to end: on two generated scenes (one where the target leaves
# the frame) `evaluate` runs our pipeline and two OpenCV trackers with TRE in 2 jobs and must
# write every output; then score_boxes, reading evaluate's box files back, must reproduce each OPE
# row of results.csv (frames, frames with ground truth, P@20, AUC, centre error: the box files
# hold what was scored, and the box-file reader reads them as written); then a scene goes through
# sequence_to_bag.py and score_bag.py (which scores with score_boxes) scores its own ground truth
# (P@20 1, AUC 20/21).
#   OT_BUILD_DIR  the catkin build (default _build)
set -euo pipefail
cd "$(dirname "$0")/../.."
export PATH=/usr/bin:/bin:/usr/sbin:/sbin:$PATH
BUILD=${OT_BUILD_DIR:-_build}
BIN=$BUILD/devel/lib/obstacle_tracker
TMP=$(mktemp -d /tmp/ot_evaluate_XXXXXX)
trap 'rm -rf "$TMP"' EXIT

for tool in evaluate generate_scene score_boxes; do
  [ -x "$BIN/$tool" ] || { echo "40-evaluate: $BIN/$tool not built"; exit 1; }
done
"$BIN/generate_scene" --scenario bird --seed 3 --frames 60 --size 320x240 --quiet --out "$TMP/data/bird"
"$BIN/generate_scene" --scenario out_of_view --seed 3 --frames 90 --size 320x240 --quiet --out "$TMP/data/out_of_view"
"$BIN/evaluate" --data "$TMP/data" --out "$TMP/out" --trackers ours-auto,ours-gt,KCF,MOSSE --jobs 2 --tre \
  --tre-segments 4 > "$TMP/stdout.md" 2> "$TMP/stderr.log" || { cat "$TMP/stderr.log"; exit 1; }
for f in results.csv results.md curves.csv boxes/bird/ours-auto.txt boxes/out_of_view/KCF.txt; do
  [ -s "$TMP/out/$f" ] || { echo "40-evaluate: missing $f"; exit 1; }
done
grep -q "^out_of_view,ours-auto,OPE,.*,[0-9.]*,[0-9.]*,[0-9.]*,[0-9.]*," "$TMP/out/results.csv" \
  || { echo "40-evaluate: no long-term scores for out_of_view"; exit 1; }
grep -q "^bird,KCF,TRE," "$TMP/out/results.csv" || { echo "40-evaluate: no TRE row"; exit 1; }
# Every row (per clip OPE and TRE, subset means) has the header's fields; a tracker started on the
# ground truth has its first box at frame 0 on the target (first_box_frame, first_box_error last).
awk -F, 'NR == 1 { n = NF } NF != n { print "40-evaluate: results.csv line " NR ": " NF " fields, header " n; bad = 1 }
         END { exit bad }' "$TMP/out/results.csv" || exit 1
grep -q "^bird,ours-gt,OPE,.*,0,0.00$" "$TMP/out/results.csv" \
  || { echo "40-evaluate: ours-gt's first box on bird is not frame 0's, on the target"; exit 1; }

# Each OPE row again from its box file. results.csv rounds to 4 decimals (2 for the centre error,
# whose slack also covers the 0.0001 px rounding of the boxes); "-" there is "nan" here.
status=0
while IFS=, read -r seq trk mode frames gt p20 auc ce rest; do
  [ "$mode" = "OPE" ] || continue
  case "$seq" in mean:*) continue ;; esac
  if ! "$BIN/score_boxes" "$TMP/out/boxes/$seq/$trk.txt" --gt "$TMP/data/$seq/groundtruth_rect.txt" \
       > "$TMP/scores.txt"; then
    echo "40-evaluate: score_boxes failed on $seq/$trk"; status=1; continue
  fi
  if ! awk -F= -v frames="$frames" -v gt="$gt" -v p20="$p20" -v auc="$auc" -v ce="$ce" '
       function near(a, b, tol) { return a - b <= tol && b - a <= tol }
       { v[$1] = $2 }
       END {
         ok = v["frames"] == frames && v["gt_frames"] == gt
         ok = ok && near(v["precision20"], p20, 0.00005 + 1e-9) && near(v["auc"], auc, 0.00005 + 1e-9)
         ce_nan = v["mean_centre_error"] == "nan"
         ok = ok && (ce == "-" ? ce_nan : !ce_nan && near(v["mean_centre_error"], ce, 0.006))
         exit !ok
       }' "$TMP/scores.txt"; then
    echo "40-evaluate: $seq/$trk: results.csv $frames frames ($gt with the target) $p20 / $auc / $ce;"
    cat "$TMP/scores.txt"; status=1
  fi
done < <(tail -n +2 "$TMP/out/results.csv")
[ $status -eq 0 ] || exit 1
echo "40-evaluate: score_boxes on the box files reproduces every OPE row of results.csv"

# Bag round trip (needs the generated Python messages of the catkin build).
export PYTHONPATH=$BUILD/devel/lib/python3/dist-packages${PYTHONPATH:+:$PYTHONPATH}
export OT_SCORE_BOXES=$BIN/score_boxes
python3 scripts/sequence_to_bag.py "$TMP/data/out_of_view" "$TMP/oov.bag" --quiet
row=$(python3 scripts/score_bag.py "$TMP/oov.bag" --gt "$TMP/data/out_of_view/groundtruth_rect.txt" \
      --topic /ground_truth 2> "$TMP/score_bag.log" | tail -1)
echo "$row" | grep -q "| 1.000 *| 0.952 " || { echo "40-evaluate: bag round trip: $row"; cat "$TMP/score_bag.log"; exit 1; }
echo "40-evaluate: bag round trip scores its own ground truth 1.000 / 0.952"
