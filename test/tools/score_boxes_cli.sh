#!/usr/bin/env bash
# Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#
# score_boxes from the outside: --help and usage errors, every input error (a missing or malformed
# file, counts that differ) as a message naming the problem and exit code 1 rather than a crash,
# the scores of boxes equal to the ground truth, and --describe of a sequence folder (its frames in
# natural name order, its fps file, its ground truth or the one --gt names).
#   usage: score_boxes_cli.sh PATH/TO/score_boxes
set -uo pipefail
TOOL=${1:?usage: score_boxes_cli.sh PATH/TO/score_boxes}
TOOL_NAME=score_boxes
# shellcheck source=cli_checks.sh
source "$(dirname "${BASH_SOURCE[0]}")/cli_checks.sh"

printf '10,10,20,20\n0,0,0,0\n30,30,10,10\n' > "$TMP/gt.txt"
printf '10,10,20,20,0.9\n0,0,0,0,0\n30,30,10,10,0.8\n' > "$TMP/same.txt"
printf '10,10,20,20,0.9\nbroken\n30,30,10,10,0.8\n' > "$TMP/malformed.txt"
printf '10,10,20,20,0.9\n0,0,0,0,0\n' > "$TMP/short.txt"
printf '10,10,20,20,0.9\n0,0,0,0,nan\n30,30,10,10,0.8\n' > "$TMP/nan_confidence.txt"
printf '10,10,20,20,0.9\n\n30,30,10,10,0.8\n' > "$TMP/blank.txt"
printf '10,10,20,20\nx y\n' > "$TMP/gt_malformed.txt"
: > "$TMP/empty.txt"

expect 0 'Usage' --help
expect 2 'score_boxes: .*--gt' "$TMP/same.txt"
expect 2 'score_boxes: BOXES is required' --gt "$TMP/gt.txt"
expect 2 'score_boxes: --print-gt takes no BOXES' "$TMP/same.txt" --gt "$TMP/gt.txt" --print-gt
expect 2 'score_boxes: ' "$TMP/same.txt" --gt "$TMP/gt.txt" --bogus
expect 1 "cannot open box file '$TMP/missing.txt'" "$TMP/missing.txt" --gt "$TMP/gt.txt"
expect 1 "cannot open ground-truth file '$TMP/missing.txt'" "$TMP/same.txt" --gt "$TMP/missing.txt"
expect 1 "malformed.txt:2: not a tracker box" "$TMP/malformed.txt" --gt "$TMP/gt.txt"
expect 1 "nan_confidence.txt:2: the confidence is not a finite number" "$TMP/nan_confidence.txt" --gt "$TMP/gt.txt"
expect 1 "blank.txt:2: blank line" "$TMP/blank.txt" --gt "$TMP/gt.txt"
expect 1 "gt_malformed.txt:2: not a box" "$TMP/same.txt" --gt "$TMP/gt_malformed.txt"
expect 1 "gt_malformed.txt:2: not a box" --gt "$TMP/gt_malformed.txt" --print-gt
expect 1 "short.txt' has 2 boxes for 3 ground-truth frames" "$TMP/short.txt" --gt "$TMP/gt.txt"
expect 1 "no box in '$TMP/empty.txt'" "$TMP/empty.txt" --gt "$TMP/gt.txt"
expect 1 "cannot open box file" "$TMP" --gt "$TMP/gt.txt"

# The ground truth scores itself: every centre within 20 px, IoU 1 (above every success threshold
# but the last, so the AUC is 20/21); the target is absent once, so the long-term scores follow.
expect 0 '^precision20=1$' "$TMP/same.txt" --gt "$TMP/gt.txt"
for line in frames=3 gt_frames=2 absent_frames=1 'auc=0.95238095[0-9]*' mean_centre_error=0 lost_fraction=0 \
            lt_precision=1 lt_recall=1 lt_fscore=1 'lt_threshold=0.80000001[0-9]*'; do
  grep -Eq "^$line\$" "$TMP/out" || { echo "FAILED: no line $line in:"; cat "$TMP/out"; failures=$((failures + 1)); }
done
expect 0 '^0,0,0,0$' --gt "$TMP/gt.txt" --print-gt
cmp -s "$TMP/out" <(printf '10,10,20,20\n0,0,0,0\n30,30,10,10\n') \
  || { echo "FAILED: --print-gt printed:"; cat "$TMP/out"; failures=$((failures + 1)); }

# --describe lists a folder's frames without decoding them, so empty files stand in for images.
mkdir -p "$TMP/seq/img"
for f in 10.png 2.png 1.png notes.txt; do : > "$TMP/seq/img/$f"; done
printf 'fps: 25\n' > "$TMP/seq/fps.txt"
cp "$TMP/gt.txt" "$TMP/seq/groundtruth_rect.txt"
expect 0 '^kind=otb_folder$' --describe "$TMP/seq"
cmp -s "$TMP/out" <(printf 'name=seq\nkind=otb_folder\nframe_count=3\nfps=25\nfile=%s\nfile=%s\nfile=%s\ngt=10,10,20,20\ngt=0,0,0,0\ngt=30,30,10,10\n' \
                    "$TMP/seq/img/1.png" "$TMP/seq/img/2.png" "$TMP/seq/img/10.png") \
  || { echo "FAILED: --describe printed:"; cat "$TMP/out"; failures=$((failures + 1)); }
printf '1,2,3,4\n' > "$TMP/other_gt.txt"
expect 0 '^gt=1,2,3,4$' --describe "$TMP/seq" --gt "$TMP/other_gt.txt"
[ "$(grep -c '^gt=' "$TMP/out")" -eq 1 ] || { echo "FAILED: --describe --gt kept the folder's ground truth"; failures=$((failures + 1)); }
expect 2 'score_boxes: --describe takes neither BOXES nor --print-gt' --describe "$TMP/seq" --print-gt
expect 1 "'$TMP/nothing' is neither a folder nor a file" --describe "$TMP/nothing"
expect 1 "is a single image" --describe "$TMP/seq/img/1.png"
expect 1 "no image or video files in '$TMP/empty_folder'" --describe "$(mkdir -p "$TMP/empty_folder" && echo "$TMP/empty_folder")"

[ "$failures" -eq 0 ] || { echo "score_boxes_cli: $failures failures"; exit 1; }
echo "score_boxes_cli: all checks passed"
