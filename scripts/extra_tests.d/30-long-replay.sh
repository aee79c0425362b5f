#!/usr/bin/env bash
# Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#
# Long replay under AddressSanitizer + LeakSanitizer: test_robust_replay (test/core) loops
# generated scenes through core::Pipeline for OT_REPLAY_FRAMES frames (default 10 000), with
# resets, parameter changes and grey/colour switches. Fails on any sanitizer report, on a leak at
# exit (detect_leaks=1) and when the heap in use grows by more than 1 MiB after warm-up.
#   OT_REPLAY_FRAMES   frames to replay (default 10000)
#   OT_ASAN_BUILD_DIR  the ASan build of 10-sanitizers.sh (default _build/asan)
set -euo pipefail
cd "$(dirname "$0")/../.."
export PATH=/usr/bin:/bin:/usr/sbin:/sbin:$PATH
BUILD=${OT_ASAN_BUILD_DIR:-_build/asan}
JOBS=${JOBS:-2}
FRAMES=${OT_REPLAY_FRAMES:-10000}

cmake -S . -B "$BUILD" -DOT_CORE_ONLY=ON -DOT_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  "-DCMAKE_CXX_FLAGS=-fsanitize=float-cast-overflow -fno-sanitize-recover=float-cast-overflow" >/dev/null
cmake --build "$BUILD" -j"$JOBS" --target test_robust_replay
export ASAN_OPTIONS="halt_on_error=1:abort_on_error=0:detect_leaks=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
export LSAN_OPTIONS="suppressions=$PWD/scripts/sanitizer_suppressions/lsan.supp:print_suppressions=0"
export OT_REPLAY_FRAMES=$FRAMES
echo "== long replay: $FRAMES frames through Pipeline::process under ASan+UBSan+LSan ($BUILD/test_robust_replay)"
"$BUILD/test_robust_replay" --gtest_brief=1
echo "== long replay: clean"
