#!/usr/bin/env bash
# Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#
# The evaluation tool end to end (issue 5): on two generated scenes (one where the target leaves
# the frame) `evaluate` runs our pipeline and two OpenCV trackers with TRE in 2 jobs and must
# write every output; then the independent Python metrics (scripts/otb_metrics.py through
# score_bag.py --boxes) must reproduce each OPE row of results.csv; then a scene goes through
# sequence_to_bag.py and score_bag.py scores its own ground truth (P@20 1, AUC 20/21).
#   OT_BUILD_DIR  the catkin build (default _build)
set -euo pipefail
cd "$(dirname "$0")/../.."
export PATH=/usr/bin:/bin:/usr/sbin:/sbin:$PATH
BUILD=${OT_BUILD_DIR:-_build}
BIN=$BUILD/devel/lib/obstacle_tracker
TMP=$(mktemp -d /tmp/ot_evaluate_XXXXXX)
trap 'rm -rf "$TMP"' EXIT

for tool in evaluate generate_scene; do
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

# Python metrics against the C++ ones, row by row (P@20, AUC, mean centre error).
status=0
while IFS=, read -r seq trk mode frames gt p20 auc ce rest; do
  [ "$mode" = "OPE" ] || continue
  case "$seq" in mean:*) continue ;; esac
  row=$(python3 scripts/score_bag.py --boxes "$TMP/out/boxes/$seq/$trk.txt" \
        --gt "$TMP/data/$seq/groundtruth_rect.txt" --name x | tail -1)
  py_p20=$(echo "$row" | awk -F'|' '{gsub(/ /,"",$5); print $5}')
  py_auc=$(echo "$row" | awk -F'|' '{gsub(/ /,"",$6); print $6}')
  # results.csv has 4 decimals, the table 3: equal within rounding.
  if ! awk -v a="$p20" -v b="$py_p20" -v c="$auc" -v d="$py_auc" \
       'BEGIN { exit !((a - b < 0.0006 && b - a < 0.0006) && (c - d < 0.0006 && d - c < 0.0006)) }'; then
    echo "40-evaluate: $seq/$trk C++ $p20/$auc, Python $py_p20/$py_auc"; status=1
  fi
done < <(tail -n +2 "$TMP/out/results.csv")
[ $status -eq 0 ] || exit 1
echo "40-evaluate: C++ and Python metrics agree on every OPE row"

# Bag round trip (needs the generated Python messages of the catkin build).
export PYTHONPATH=$BUILD/devel/lib/python3/dist-packages${PYTHONPATH:+:$PYTHONPATH}
python3 scripts/sequence_to_bag.py "$TMP/data/out_of_view" "$TMP/oov.bag" --quiet
row=$(python3 scripts/score_bag.py "$TMP/oov.bag" --gt "$TMP/data/out_of_view/groundtruth_rect.txt" \
      --topic /ground_truth 2>/dev/null | tail -1)
echo "$row" | grep -q "| 1.000 *| 0.952 " || { echo "40-evaluate: bag round trip: $row"; exit 1; }
echo "40-evaluate: bag round trip scores its own ground truth 1.000 / 0.952"
