#!/usr/bin/env bash
# Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#
# track_sequence from the outside: --help and usage errors (exit 2), input and output errors as a
# message naming the problem and exit code 1 (a missing input, a folder without frames, a full
# disk), and on a short generated scene one line of six values per frame.
#   usage: track_sequence_cli.sh PATH/TO/track_sequence   (generate_scene is taken from beside it)
set -uo pipefail
TOOL=${1:?usage: track_sequence_cli.sh PATH/TO/track_sequence}
GENERATE=$(dirname "$TOOL")/generate_scene
TOOL_NAME=track_sequence
# shellcheck source=cli_checks.sh
source "$(dirname "${BASH_SOURCE[0]}")/cli_checks.sh"

if ! "$GENERATE" --scenario crossing --frames 12 --size 320x240 --quiet --out "$TMP/scene" > /dev/null; then
  echo "FAILED: generate_scene could not make the test scene"
  exit 1
fi
mkdir -p "$TMP/no_frames"
cp -r "$TMP/scene/img" "$TMP/no_truth"  # frames without a ground-truth file

expect 0 'Usage' --help
expect 2 'track_sequence: .*INPUT' --quiet
expect 2 'track_sequence: ' "$TMP/scene" --bogus
expect 1 'track_sequence: error: .*missing' "$TMP/missing"
expect 1 'track_sequence: error: ' "$TMP/no_frames"
expect 2 'track_sequence: --init gt but .* has no ground truth' "$TMP/no_truth" --init gt
if [ -w /dev/full ]; then
  "$TOOL" "$TMP/scene" --init gt --quiet > /dev/full 2> "$TMP/err"
  code=$?
  if [ "$code" -ne 1 ] || ! grep -q "write error on 'stdout'" "$TMP/err"; then
    echo "FAILED: track_sequence > /dev/full: exit $code (want 1 and a write error):"
    cat "$TMP/err"
    failures=$((failures + 1))
  fi
  expect 1 "write error on '/dev/full'" "$TMP/scene" --init gt --quiet --output /dev/full
fi

# One line per frame, x,y,w,h,confidence,time_to_contact; started from the truth, frame 1's box
# is the truth's first box.
expect 0 '' "$TMP/scene" --init gt --quiet
lines=$(wc -l < "$TMP/out")
bad=$(grep -Evc '^-?[0-9.]+,-?[0-9.]+,[0-9.]+,[0-9.]+,[0-9.]+,(inf|-?[0-9.]+)$' "$TMP/out")
if [ "$lines" -ne 12 ] || [ "$bad" -ne 0 ]; then
  echo "FAILED: track_sequence --init gt: $lines lines (want 12), $bad not of six values:"
  cat "$TMP/out"
  failures=$((failures + 1))
fi

if [ "$failures" -ne 0 ]; then
  echo "$failures check(s) failed"
  exit 1
fi
echo "track_sequence_cli: all checks passed"
