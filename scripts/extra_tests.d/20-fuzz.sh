#!/usr/bin/env bash
# Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#
# Bounded libFuzzer runs (clang, ASan + UBSan) of every fuzz target in fuzz/: fuzz_params (the
# parameter loader and setters) and fuzz_pipeline (the core Pipeline on random frames, stamps and
# parameters). Each starts from seed corpora written by fuzz_make_seeds and runs FUZZ_RUNS inputs
# or FUZZ_SECONDS, whichever ends first; the targets run side by side, one core each.
# Any crash, sanitizer report, broken invariant, uncaught exception, input slower than 20 s or
# RSS above 2 GiB fails the script; the input that did it is kept in $BUILD/artifacts/ (replay:
# $BUILD/fuzz_NAME $BUILD/artifacts/crash-...; add it to test/core/test_robust_fuzz.cpp).
#   FUZZ_SECONDS      upper bound in seconds per target (default 120)
#   FUZZ_RUNS         inputs per target (default: 30000 for fuzz_params, 8000 for fuzz_pipeline,
#                     0 = no bound, FUZZ_SECONDS alone)
#   FUZZ_SEED         libFuzzer's random seed (default 1). A fixed seed and a run count make
#                     the CI run a bounded, nearly repeatable walk (a faster machine does not
#                     explore further; two runs here added 1101/1060 and 735/704 corpus units, so
#                     not bit-identical), and a finding's input is kept to replay; 0 = a new seed
#                     each run, for longer local hunts (FUZZ_SEED=0 FUZZ_RUNS=0 FUZZ_SECONDS=600).
#   OT_FUZZ_BUILD_DIR build folder (default _build/fuzz)
#   JOBS              parallel build jobs (default 2)
set -euo pipefail
cd "$(dirname "$0")/../.."
export PATH=/usr/bin:/bin:/usr/sbin:/sbin:$PATH
BUILD=${OT_FUZZ_BUILD_DIR:-_build/fuzz}
SECONDS_EACH=${FUZZ_SECONDS:-120}
SEED=${FUZZ_SEED:-1}
JOBS=${JOBS:-2}

if ! command -v clang++ >/dev/null; then
  echo "FAILED: clang++ not found (Debian packages clang libclang-rt-14-dev, see scripts/setup.sh)"
  exit 1
fi
echo "== fuzz: core-only clang build with libFuzzer + ASan + UBSan in $BUILD"
CC=clang CXX=clang++ cmake -S . -B "$BUILD" -DOT_CORE_ONLY=ON -DOT_FUZZ=ON \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$BUILD" -j"$JOBS" --target fuzzers

rm -rf "$BUILD/seeds"
"$BUILD/fuzz_make_seeds" "$BUILD/seeds"
mkdir -p "$BUILD/artifacts"
export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1:abort_on_error=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
# One target on one core: the targets run side by side (each libFuzzer process is one thread),
# and each one's report is printed when it ends.
fuzz_target() {
  local target=$1 name runs corpus log
  name=$(basename "$target")
  corpus=$BUILD/corpus/$name
  mkdir -p "$corpus"
  log=$BUILD/$name.log
  case "$name" in
    fuzz_params) runs=${FUZZ_RUNS:-30000} ;;
    *) runs=${FUZZ_RUNS:-8000} ;;
  esac
  [ "$runs" -gt 0 ] || runs=-1
  echo "== fuzz: $name, seed $SEED, $runs runs or ${SECONDS_EACH}s (corpus $corpus, seeds $BUILD/seeds/$name, log $log)"
  if "$target" -seed="$SEED" -runs="$runs" -max_total_time="$SECONDS_EACH" -timeout=20 -rss_limit_mb=2048 -max_len=8192 \
      -print_final_stats=1 -artifact_prefix="$BUILD/artifacts/$name-" \
      "$corpus" "$BUILD/seeds/$name" >"$log" 2>&1; then
    grep -E '^stat::(number_of_executed_units|average_exec_per_sec|new_units_added)' "$log" || true
    echo "== fuzz: $name clean"
  else
    echo "FAILED: $name found a problem; last lines of $log:"
    tail -n 60 "$log"
    ls -l "$BUILD/artifacts/" | grep "$name" || true
    return 1
  fi
}
status=0
pids=()
reports=()
for target in "$BUILD"/fuzz_*; do
  name=$(basename "$target")
  [ -x "$target" ] && [ "$name" != fuzz_make_seeds ] || continue
  reports+=("$BUILD/$name.report")
  fuzz_target "$target" >"$BUILD/$name.report" 2>&1 &
  pids+=($!)
done
ran=${#pids[@]}
for i in "${!pids[@]}"; do
  wait "${pids[$i]}" || status=1
  cat "${reports[$i]}"
done
if [ "$ran" -eq 0 ]; then
  echo "FAILED: no fuzz target was built"
  exit 1
fi
exit $status
