#!/usr/bin/env bash
# Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#
# The core's unit and sequence tests again, built with AddressSanitizer + UndefinedBehaviorSanitizer
# (and LeakSanitizer, part of ASan on Linux). Any report is fatal: the test that triggered it fails
# and this script exits non-zero.
# Beside them (one thread, so it shares the cores with the suite instead of running after it), the
# long replay: test_robust_replay (test/core) loops generated scenes through core::Pipeline for
# OT_REPLAY_FRAMES frames, with resets, parameter changes and grey/colour switches on a fixed
# schedule. It fails on any sanitizer report, on a leak at exit and when the highest heap in use
# over the schedule's last period exceeds that over its first by more than 1 MiB.
#   OT_ASAN_BUILD_DIR  build folder (default _build/asan)
#   OT_REPLAY_FRAMES   frames of the long replay (default 10000)
#   JOBS               parallel build jobs (default 2)
set -euo pipefail
cd "$(dirname "$0")/../.."
export PATH=/usr/bin:/bin:/usr/sbin:/sbin:$PATH
BUILD=${OT_ASAN_BUILD_DIR:-_build/asan}
JOBS=${JOBS:-2}
FRAMES=${OT_REPLAY_FRAMES:-10000}

echo "== sanitizers: core-only ASan+UBSan build in $BUILD"
# GCC's -fsanitize=undefined leaves out float-cast-overflow (a NaN or huge float converted to int,
# the classic bug of box arithmetic): added here.
cmake -S . -B "$BUILD" -DOT_CORE_ONLY=ON -DOT_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  "-DCMAKE_CXX_FLAGS=-fsanitize=float-cast-overflow -fno-sanitize-recover=float-cast-overflow" >/dev/null
cmake --build "$BUILD" -j"$JOBS" --target tests

# Suppressions cover only third-party libraries we do not build (none needed so far: the file
# exists so that one can be added with a reason, never to hide our own code).
SUPP=$PWD/scripts/sanitizer_suppressions
export ASAN_OPTIONS="halt_on_error=1:abort_on_error=0:detect_leaks=1:detect_stack_use_after_return=1:strict_init_order=1:check_initialization_order=1:detect_odr_violation=2"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:report_error_type=1"
export LSAN_OPTIONS="suppressions=$SUPP/lsan.supp:print_suppressions=0"

REPLAY_LOG=$BUILD/long_replay.log
echo "== long replay: $FRAMES frames through Pipeline::process under ASan+UBSan+LSan, beside the suite (log $REPLAY_LOG)"
# The replay's own options: stack-use-after-return detection would slow 10 000 frames for no
# gain here, the suite runs with it.
OT_REPLAY_FRAMES=$FRAMES ASAN_OPTIONS="halt_on_error=1:abort_on_error=0:detect_leaks=1" \
  "$BUILD/test_robust_replay" --gtest_brief=1 >"$REPLAY_LOG" 2>&1 &
REPLAY=$!
trap 'kill "$REPLAY" 2>/dev/null || true' EXIT

status=0
echo "== sanitizers: ctest in $BUILD (ASAN_OPTIONS=$ASAN_OPTIONS UBSAN_OPTIONS=$UBSAN_OPTIONS)"
ctest --test-dir "$BUILD" -j"$JOBS" --output-on-failure --timeout 600 || status=1
replay_status=0
wait "$REPLAY" || replay_status=$?
trap - EXIT
cat "$REPLAY_LOG"
if [ "$replay_status" -ne 0 ]; then
  echo "FAILED: long replay (exit $replay_status)"
  status=1
fi
[ "$status" -eq 0 ] && echo "== sanitizers and long replay: clean"
exit $status
