#!/usr/bin/env bash
# Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#
# Rewrites docs/results.md as evaluate's own report: every tracker on the dev clips in one run
# (the speeds are only comparable within a run), with its plots in docs/results/. The figures
# in README's "Results" come from this report; the other measurements are in
# docs/measurements.md.
#   OT_BUILD_DIR  the catkin build (default _build)
#   OT_DATA       the sequences (default ../shared/sequences)
#   OT_JOBS       parallel jobs (default 2)
set -euo pipefail
cd "$(dirname "$0")/.."
export PATH=/usr/bin:/bin:/usr/sbin:/sbin:$PATH
BUILD=${OT_BUILD_DIR:-_build}
DATA=${OT_DATA:-../shared/sequences}
OUT=_results
EVALUATE=$BUILD/devel/lib/obstacle_tracker/evaluate
[ -x "$EVALUATE" ] || { echo "update_results: $EVALUATE not built (bash scripts/setup.sh build)" >&2; exit 1; }
[ -d "$DATA" ] || { echo "update_results: no sequences at $DATA (set OT_DATA)" >&2; exit 1; }

"$EVALUATE" --data "$DATA" --out "$OUT" --jobs "${OT_JOBS:-2}" \
  --trackers ours-gt,ours-auto,CSRT,KCF,MOSSE,MIL,MedianFlow
mkdir -p docs/results
rm -f docs/results/*.png
cp "$OUT"/*.png docs/results/ 2>/dev/null || echo "update_results: no plots (python3-matplotlib missing?)" >&2
# The report links its plots beside it; in docs/ they live in docs/results/.
sed -E 's/^!\[([^]]*)\]\(([^/)]*\.png)\)$/![\1](results\/\2)/' "$OUT/results.md" > docs/results.md
echo "update_results: wrote docs/results.md and docs/results/*.png from $OUT"
