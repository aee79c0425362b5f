#!/usr/bin/env bash
# The built-in demo (README "Quick start"): renders a generated flight scene with ground truth,
# runs the tracker on it with no initial box (auto-initialisation), writes an overlay video, and
# scores it side by side with OpenCV's KCF and CSRT (started from ground truth) in one run.
# Needs a build in _build (bash scripts/setup.sh build). Outputs in _demo/.
#   DEMO_SCENARIO (default crossing), DEMO_SEED (3), DEMO_FRAMES (150), DEMO_SIZE (640x480)
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=_build/devel/lib/obstacle_tracker
[ -x "$BIN/track_sequence" ] || BIN=_build
for tool in generate_scene track_sequence evaluate; do
  if [ ! -x "$BIN/$tool" ]; then
    echo "demo: $BIN/$tool is missing; build first: bash scripts/setup.sh build" >&2
    exit 1
  fi
done
SCENARIO=${DEMO_SCENARIO:-crossing}
SEED=${DEMO_SEED:-3}
FRAMES=${DEMO_FRAMES:-150}
SIZE=${DEMO_SIZE:-640x480}
OUT=_demo
rm -rf "$OUT"
mkdir -p "$OUT/scenes"

echo "== generating scene '$SCENARIO' (seed $SEED, $FRAMES frames, $SIZE) into $OUT/scenes/$SCENARIO"
"$BIN/generate_scene" --scenario "$SCENARIO" --seed "$SEED" --frames "$FRAMES" --size "$SIZE" \
  --out "$OUT/scenes/$SCENARIO" --quiet

echo "== tracking with no initial box (--init auto)"
"$BIN/track_sequence" "$OUT/scenes/$SCENARIO" --init auto --output "$OUT/result.txt" \
  --overlay "$OUT/overlay.mp4" --quiet

echo "== scoring against ground truth, beside OpenCV KCF and CSRT (same run)"
"$BIN/evaluate" --data "$OUT/scenes" --out "$OUT/eval" --trackers ours-auto,ours-gt,KCF,CSRT \
  --jobs 2 > "$OUT/evaluate.log" 2>&1 || { cat "$OUT/evaluate.log" >&2; exit 1; }
cp "$OUT/eval/results.md" "$OUT/results.md"

sed -n '/^## Overall (OPE)/,/^## Per sequence/p' "$OUT/results.md" | sed '$d'
echo
echo "Demo outputs:"
echo "  $OUT/overlay.mp4     the frames with the tracker's box, id, confidence and state"
echo "  $OUT/result.txt      x,y,w,h,confidence,time_to_contact per frame (0,0,0,0,0,inf when nothing is tracked)"
echo "  $OUT/results.md      accuracy (OTB precision@20 px, success AUC) and fps, with KCF and CSRT"
echo "  $OUT/eval/           per-frame boxes, curves and precision/success plots"
echo "  $OUT/scenes/$SCENARIO/  the generated frames and ground truth"
